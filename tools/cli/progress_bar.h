// A terminal progress bar with an ETA: drawn on stderr only when it is a terminal and not quiet,
// so logs stay clean.
#pragma once

#include <chrono>
#include <string>

namespace penumbra::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ~ProgressBar();
  void update(int done, int total, const std::string& step);
  // Ends the bar's line, so that what is printed next starts a line of its own; the next update
  // draws the bar again below it.
  void breakLine();

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace penumbra::cli
