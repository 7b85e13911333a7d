// Time of one pass, two ways: GL_TIME_ELAPSED queries (GPU time, exact on vendor drivers) and
// wall-clock time between glFinish calls (what a software rasteriser such as llvmpipe, whose
// queries see only command submission, actually spends). One span at a time.
#pragma once

#include <chrono>

namespace penumbra::gl {

class GpuTimer {
 public:
  GpuTimer();
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin();
  void end();
  void reset();  // the pass did not run: both times read 0
  double gpuMilliseconds() const;  // waits for the query result
  double wallMilliseconds() const { return wallMilliseconds_; }

 private:
  unsigned query_ = 0;
  bool used_ = false;
  std::chrono::steady_clock::time_point start_;
  double wallMilliseconds_ = 0.0;
};

}  // namespace penumbra::gl
