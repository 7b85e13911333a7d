// Timer queries and synchronised wall-clock spans.
#include "gpu_timer.h"

#include <epoxy/gl.h>

namespace penumbra::gl {

GpuTimer::GpuTimer() {
  glCreateQueries(GL_TIME_ELAPSED, 1, &query_);
}

GpuTimer::~GpuTimer() {
  glDeleteQueries(1, &query_);
}

void GpuTimer::begin() {
  glFinish();
  start_ = std::chrono::steady_clock::now();
  glBeginQuery(GL_TIME_ELAPSED, query_);
  used_ = true;
}

void GpuTimer::end() {
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
  if (!used_) return 0.0;
  GLuint64 nanoseconds = 0;
  glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &nanoseconds);
  return double(nanoseconds) * 1e-6;
}

}  // namespace penumbra::gl
