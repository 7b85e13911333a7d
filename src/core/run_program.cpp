// Spawning external tools with posix_spawnp: an argument vector, never a shell.
#include "penumbra/run_program.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

#include "penumbra/error.h"

extern char** environ;

namespace penumbra {

ProgramResult runProgram(const std::vector<std::string>& args, const std::filesystem::path& log) {
  if (args.empty()) throw Error("runProgram: no program named");
  std::vector<std::string> copies = args;
  std::vector<char*> argv;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);

  int logFd = -1;
  if (!log.empty()) {
    logFd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (logFd < 0) {
      throw Error("cannot create " + log.string() + " for " + args[0] + "'s messages: " +
                  std::strerror(errno));
    }
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // No input: a tool that reads its terminal (ffmpeg) would stop a background run on SIGTTIN.
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  if (logFd >= 0) {
    posix_spawn_file_actions_adddup2(&actions, logFd, 1);
    posix_spawn_file_actions_adddup2(&actions, logFd, 2);
  } else {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  }
  // The child starts with no signal blocked and SIGINT/SIGTERM at their defaults: the CLI blocks
  // them in every thread for its interrupt watcher (tools/cli/interrupt_cleanup.h), and a child
  // inheriting that mask would outlive a Ctrl-C.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  const int spawnError = posix_spawnp(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (logFd >= 0) ::close(logFd);

  ProgramResult result;
  if (spawnError != 0) return result;
  result.started = true;
  int status = 0;
  pid_t waited = 0;
  do {
    waited = waitpid(pid, &status, 0);
  } while (waited == -1 && errno == EINTR);
  if (waited == pid && WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
  return result;
}

}  // namespace penumbra
