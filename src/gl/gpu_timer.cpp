// Timer queries and synchronised wall-clock spans.
#include "gpu_timer.h"

#include <epoxy/gl.h>

namespace penumbra::gl {

GpuTimer::~GpuTimer() {
  if (query_ != 0) glDeleteQueries(1, &query_);
}

void GpuTimer::setEnabled(bool enabled) {
  if (enabled != enabled_) reset();  // no time from before the switch reads as current
  enabled_ = enabled;
}

void GpuTimer::begin() {
  if (!enabled_) return;
  if (query_ == 0) glCreateQueries(GL_TIME_ELAPSED, 1, &query_);
  glFinish();
  start_ = std::chrono::steady_clock::now();
  glBeginQuery(GL_TIME_ELAPSED, query_);
  used_ = true;
  running_ = true;
}

void GpuTimer::end() {
  if (!running_) return;
  running_ = false;
  glEndQuery(GL_TIME_ELAPSED);
  glFinish();
  wallMilliseconds_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
}

void GpuTimer::reset() {
  used_ = false;
  wallMilliseconds_ = 0.0;
}

double GpuTimer::gpuMilliseconds() const {
  if (!enabled_ || !used_) return 0.0;
  GLuint64 nanoseconds = 0;
  glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &nanoseconds);
  return double(nanoseconds) * 1e-6;
}

}  // namespace penumbra::gl
