// Runs the `penumbra` command as a child process (fork/exec, so arguments such as '' pass through
// unchanged) in a chosen working folder, and scratch folders for the tests that do.
#pragma once

#include <fcntl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::test {

namespace fs = std::filesystem;

struct RunResult {
  int status = 0;      // the raw waitpid status
  std::string output;  // stdout and stderr together
  int exitCode() const { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }
};

// Environment variables set for the child only.
using Environment = std::vector<std::pair<std::string, std::string>>;

// Starts penumbra with `args` in `cwd`; its stdout and stderr go to `log`.
inline pid_t startPenumbra(const std::vector<std::string>& args, const fs::path& cwd,
                           const fs::path& log, const Environment& environment = {}) {
  std::vector<std::string> all{PENUMBRA_EXECUTABLE};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || dup2(fd, 1) < 0 || dup2(fd, 2) < 0 || chdir(cwd.c_str()) != 0) _exit(127);
    for (const auto& [name, value] : environment) setenv(name.c_str(), value.c_str(), 1);
    execv(argv[0], argv.data());
    _exit(127);
  }
  if (pid < 0) throw std::runtime_error("fork failed");
  return pid;
}

inline std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs penumbra to completion.
inline RunResult runPenumbra(const std::vector<std::string>& args, const fs::path& cwd,
                             const Environment& environment = {}) {
  const fs::path log = cwd / ".penumbra-test-output";
  const pid_t pid = startPenumbra(args, cwd, log, environment);
  RunResult result;
  waitpid(pid, &result.status, 0);
  result.output = readFile(log);
  fs::remove(log);
  return result;
}

// A fresh folder under the system's temporary folder, removed with everything in it at the end.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "penumbra-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Writes `text` to `path`, creating its folder.
inline void writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// Every entry below `folder`: files with their contents, folders and links marked as such (so a
// new empty folder, a staging folder left behind or a link counts as a change), for "left
// untouched" checks.
inline std::vector<std::pair<std::string, std::string>> snapshot(const fs::path& folder) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string name = fs::relative(entry.path(), folder).string();
    if (entry.is_symlink()) {
      files.emplace_back(name, "<link to " + fs::read_symlink(entry.path()).string() + ">");
    } else if (entry.is_directory()) {
      files.emplace_back(name, "<folder>");
    } else {
      files.emplace_back(name, readFile(entry.path()));
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Names in `folder` that start with `prefix` (staging and set-aside folders of a target).
inline std::vector<std::string> entriesStartingWith(const fs::path& folder,
                                                    const std::string& prefix) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) == 0) names.push_back(name);
  }
  return names;
}

}  // namespace penumbra::test
