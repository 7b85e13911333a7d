// The sigwait watcher behind InterruptCleanup.
#include "interrupt_cleanup.h"

#include <pthread.h>

#include <ctime>

namespace penumbra::cli {

InterruptCleanup::InterruptCleanup() {
  sigemptyset(&signals_);
  sigaddset(&signals_, SIGINT);
  sigaddset(&signals_, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals_, &previousMask_);
  watcher_ = std::thread([this] { watch(); });
}

InterruptCleanup::~InterruptCleanup() {
  stopping_ = true;
  watcher_.join();
  pthread_sigmask(SIG_SETMASK, &previousMask_, nullptr);
}

void InterruptCleanup::setCleanup(std::function<void()> cleanup) {
  std::lock_guard lock(mutex_);
  cleanup_ = std::move(cleanup);
}

void InterruptCleanup::uninterrupted(const std::function<void()>& step) {
  std::lock_guard lock(mutex_);
  step();
}

void InterruptCleanup::watch() {
  // Wakes every 100 ms to notice the destructor.
  const timespec period{0, 100'000'000};
  while (!stopping_) {
    const int signal = sigtimedwait(&signals_, nullptr, &period);
    if (signal != SIGINT && signal != SIGTERM) continue;
    {
      std::lock_guard lock(mutex_);  // waits for an uninterrupted step to finish
      if (cleanup_) cleanup_();
    }
    // Die of the signal as if it had never been caught.
    struct sigaction action {};
    action.sa_handler = SIG_DFL;
    sigaction(signal, &action, nullptr);
    sigset_t only;
    sigemptyset(&only);
    sigaddset(&only, signal);
    pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
    raise(signal);
  }
}

}  // namespace penumbra::cli
