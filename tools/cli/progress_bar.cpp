// Progress bar drawing.
#include "progress_bar.h"

#include <unistd.h>

#include <cstdio>

namespace penumbra::cli {

ProgressBar::ProgressBar(bool quiet)
    : enabled_(!quiet && isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fprintf(stderr, "\n");
}

void ProgressBar::breakLine() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

void ProgressBar::update(int done, int total, const std::string& step) {
  if (!enabled_ || total <= 0) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fraction = double(done) / double(total);
  const int eta = done > 0 ? int(elapsed / done * (total - done) + 0.5) : -1;
  char bar[31];
  const int filled = int(fraction * 30.0);
  for (int i = 0; i < 30; ++i) bar[i] = i < filled ? '#' : '.';
  bar[30] = '\0';
  char etaText[32] = "--:--";
  if (eta >= 0) std::snprintf(etaText, sizeof etaText, "%d:%02d", eta / 60, eta % 60);
  std::fprintf(stderr, "\r[%s] %3d%%  ETA %s  %-40.40s", bar, int(fraction * 100.0), etaText,
               step.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace penumbra::cli
