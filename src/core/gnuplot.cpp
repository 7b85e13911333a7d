// gnuplot invocation: a script in a private folder, run without a shell.
#include "penumbra/gnuplot.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

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

GnuplotRun::GnuplotRun(const fs::path& folder) {
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

void GnuplotRun::add(const std::string& figure) {
  // `reset` leaves the terminal and output alone; each figure sets its own. `unset output`
  // closes each figure's file once it is drawn rather than when the next figure opens its own.
  script_ += "reset\n" + figure + (figure.empty() || figure.back() == '\n' ? "" : "\n") +
             "unset output\n";
  ++figures_;
}

void GnuplotRun::run(const std::string& script) {
  add(script);
  run();
}

void GnuplotRun::run() {
  const fs::path scriptPath = scratch_ / "plot.gp";
  const fs::path logPath = scratch_ / "gnuplot.log";
  writeNewFile(scriptPath, script_);
  script_.clear();
  recordOutput(logPath);
  const ProgramResult result = runProgram({"gnuplot", scriptPath.string()}, logPath);
  std::error_code ec;
  fs::remove(scriptPath, ec);
  if (!result.started) {
    throw Error("gnuplot is not installed: run scripts/install-deps (Debian package gnuplot-nox)");
  }
  std::ifstream logFile(logPath);
  std::stringstream log;
  log << logFile.rdbuf();
  fs::remove(logPath, ec);
  if (!result.succeeded()) {
    std::string message = log.str();
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    if (message.empty()) {
      message = result.exitCode < 0 ? "killed by a signal"
                                    : "exit status " + std::to_string(result.exitCode);
    }
    throw Error("gnuplot failed: " + message);
  }
}

}  // namespace penumbra
