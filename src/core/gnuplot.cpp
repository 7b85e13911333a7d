// gnuplot invocation: a script in a private folder, run without a shell.
#include "penumbra/gnuplot.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "penumbra/error.h"
#include "penumbra/output_journal.h"
#include "penumbra/run_program.h"

namespace penumbra {
namespace fs = std::filesystem;

namespace {

bool isControl(char c) {
  return (unsigned char)c < 0x20 || c == 0x7f;
}

std::string singleQuoted(std::string_view text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += '\'';
    out += c;
  }
  return out + "'";
}

// Writes `text` to a file that must not exist yet (the private folder is ours alone, but a
// file is still never written through a link).
void writeNewFile(const fs::path& path, const std::string& text) {
  recordOutput(path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) throw Error("cannot create " + path.string() + ": " + std::strerror(errno));
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      throw Error("cannot write " + path.string() + ": " + reason);
    }
    written += size_t(n);
  }
  ::close(fd);
}

}  // namespace

std::string gnuplotText(std::string_view text) {
  std::string clean(text);
  for (char& c : clean) {
    if (isControl(c)) c = '?';
  }
  return singleQuoted(clean);
}

std::string gnuplotPath(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) throw Error("cannot resolve " + path.string() + ": " + ec.message());
  const std::string text = absolute.string();
  for (char c : text) {
    if (isControl(c)) {
      throw Error("the path " + gnuplotText(text) +
                  " holds a control character (a line break, tab or escape), which gnuplot "
                  "cannot be given safely; choose another name");
    }
  }
  return singleQuoted(text);
}

std::string gnuplotOutput(const fs::path& path) {
  std::string quoted = gnuplotPath(path);
  recordOutput(path);
  return quoted;
}

GnuplotRun::GnuplotRun(const fs::path& folder, int processes)
    : processes_(processes > 0
                     ? processes
                     : std::clamp(int(std::thread::hardware_concurrency()), 1, kMaxProcesses)) {
  std::string pattern = (folder / ".gnuplot-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw Error("cannot create a private folder for gnuplot in " + folder.string() + ": " +
                std::strerror(errno));
  }
  scratch_ = pattern;
  // Listed as soon as it exists (mkdtemp chose the name): a killed run's next run removes it.
  recordOutput(scratch_);
}

GnuplotRun::~GnuplotRun() {
  std::error_code ec;
  fs::remove_all(scratch_, ec);
}

fs::path GnuplotRun::scratchFile(std::string_view name) const {
  const fs::path file(name);
  if (file.empty() || file.has_parent_path() || name == "." || name == "..") {
    throw Error("gnuplot scratch file name '" + std::string(name) + "' is not a plain file name");
  }
  recordOutput(scratch_ / file);
  return scratch_ / file;
}

void GnuplotRun::add(const std::string& figure, double pixels) {
  // `reset` leaves the terminal and output alone; each figure sets its own. `unset output`
  // closes each figure's file once it is drawn rather than when the next figure opens its own.
  figures_.push_back({"reset\n" + figure + (figure.empty() || figure.back() == '\n' ? "" : "\n") +
                          "unset output\n",
                      std::max(pixels, 1.0)});
  ++figureCount_;
}

void GnuplotRun::run(const std::string& script) {
  add(script);
  run();
}

void GnuplotRun::run() {
  // The largest figure first to the least loaded process (LPT scheduling), each process's
  // figures kept in the order they were added.
  const size_t count = std::min(figures_.size(), size_t(processes_));
  std::vector<size_t> order(figures_.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return figures_[a].pixels > figures_[b].pixels; });
  std::vector<double> load(count, 0.0);
  std::vector<std::vector<size_t>> assigned(count);
  for (size_t i : order) {
    const size_t p = size_t(std::min_element(load.begin(), load.end()) - load.begin());
    load[p] += figures_[i].pixels;
    assigned[p].push_back(i);
  }
  struct Process {
    fs::path script;
    fs::path log;
    ProgramResult result;
  };
  std::vector<Process> processes(count);
  for (size_t p = 0; p < count; ++p) {
    std::sort(assigned[p].begin(), assigned[p].end());
    std::string script;
    for (size_t i : assigned[p]) script += figures_[i].script;
    processes[p].script = scratch_ / ("plot-" + std::to_string(p) + ".gp");
    processes[p].log = scratch_ / ("gnuplot-" + std::to_string(p) + ".log");
    writeNewFile(processes[p].script, script);
    recordOutput(processes[p].log);
  }
  figures_.clear();
  std::vector<std::string> spawnErrors(count);
  {
    // runProgram creates the log (or throws when it cannot) and waits for its own child only.
    // jthreads join when this scope ends, also when starting one of them throws.
    auto draw = [&](size_t p) {
      try {
        processes[p].result =
            runProgram({"gnuplot", processes[p].script.string()}, processes[p].log);
      } catch (const Error& e) {
        spawnErrors[p] = e.what();
      }
    };
    std::vector<std::jthread> others;
    for (size_t p = 1; p < count; ++p) others.emplace_back(draw, p);
    if (count > 0) draw(0);
  }
  // Every process's script and log are removed before any error is reported, so the run can
  // queue and draw again.
  std::string failure;
  bool installed = true;
  for (const Process& process : processes) {
    std::error_code ec;
    fs::remove(process.script, ec);
    std::ifstream logFile(process.log);
    std::stringstream log;
    log << logFile.rdbuf();
    logFile.close();
    fs::remove(process.log, ec);
    installed = installed && process.result.started;
    if (!process.result.started || process.result.succeeded() || !failure.empty()) continue;
    failure = log.str();
    while (!failure.empty() && (failure.back() == '\n' || failure.back() == ' '))
      failure.pop_back();
    if (failure.empty()) {
      failure = process.result.exitCode < 0
                    ? "killed by a signal"
                    : "exit status " + std::to_string(process.result.exitCode);
    }
  }
  for (const std::string& e : spawnErrors) {
    if (!e.empty()) throw Error(e);
  }
  if (!installed) {
    throw Error("gnuplot is not installed: run scripts/install-deps (Debian package gnuplot-nox)");
  }
  if (!failure.empty()) throw Error("gnuplot failed: " + failure);
}

}  // namespace penumbra
