// Time of one pass, two ways: GL_TIME_ELAPSED queries (GPU time, exact on vendor drivers) and
// wall-clock time between glFinish calls (what a software rasteriser such as llvmpipe, whose
// queries see only command submission, actually spends). One span at a time. Timing stalls the
// pipeline, so it can be switched off (a host's frame): a disabled timer issues no GL call.
#pragma once

#include <chrono>

namespace penumbra::gl {

class GpuTimer {
 public:
  GpuTimer() = default;  // makes its query on first use: constructing needs no context
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // Enabled by default. Disabled: begin() and end() do nothing and both times read 0. A span
  // already begun still ends at end().
  void setEnabled(bool enabled);
  bool enabled() const { return enabled_; }

  void begin();
  void end();
  void reset();                    // the pass did not run: both times read 0
  double gpuMilliseconds() const;  // waits for the query result
  double wallMilliseconds() const { return enabled_ ? wallMilliseconds_ : 0.0; }
  // The query's time where it measures execution (Renderer::timerQueriesMeasureExecution), else
  // the wall clock's.
  double milliseconds(bool queriesMeasureExecution) const {
    return queriesMeasureExecution ? gpuMilliseconds() : wallMilliseconds();
  }

 private:
  bool enabled_ = true;
  bool running_ = false;  // between begin() and end()
  unsigned query_ = 0;
  bool used_ = false;
  std::chrono::steady_clock::time_point start_;
  double wallMilliseconds_ = 0.0;
};

}  // namespace penumbra::gl
