// SIGINT and SIGTERM during a long run: remove what this run created, then die of the signal.
// No code runs in a signal handler: the signals are blocked in every thread and a watcher thread
// takes them with sigwait, runs the cleanup, restores the default action and raises the signal
// again, so the exit status still says "killed by SIGINT". SIGKILL cannot be caught; the next
// run removes what a killed run left (report_folder.h).
#pragma once

#include <signal.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <thread>

namespace penumbra::cli {

class InterruptCleanup {
 public:
  // Blocks SIGINT and SIGTERM in the calling thread and so in every thread it starts later
  // (construct it before the GL context, whose driver threads must inherit the mask).
  InterruptCleanup();
  ~InterruptCleanup();  // stops the watcher and restores the signal mask
  InterruptCleanup(const InterruptCleanup&) = delete;
  InterruptCleanup& operator=(const InterruptCleanup&) = delete;

  // What a signal runs before the process dies; replaces the previous cleanup.
  void setCleanup(std::function<void()> cleanup);
  // Runs `step` to completion before a signal is acted on (creating or swapping in a folder).
  void uninterrupted(const std::function<void()>& step);

 private:
  void watch();

  sigset_t signals_{};
  sigset_t previousMask_{};
  std::recursive_mutex mutex_;
  std::function<void()> cleanup_;
  std::atomic<bool> stopping_{false};
  std::thread watcher_;
};

}  // namespace penumbra::cli
