// GpuTimer's switch: a disabled timer makes no GL call (no glFinish stalls a host's frame, no
// query) and reads 0; an enabled one, the default, times as before.
#include "gpu_timer.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl_test_context.h"

namespace penumbra {
namespace {

class GpuTiming : public testing::GlTest {};

// Counts the calls a timer makes by swapping libepoxy's dispatch pointers for counting wrappers.
struct TimerCallCounter {
  static inline int count = 0;
  static inline PFNGLFINISHPROC finish = nullptr;
  static inline PFNGLCREATEQUERIESPROC createQueries = nullptr;
  static inline PFNGLBEGINQUERYPROC beginQuery = nullptr;
  static inline PFNGLENDQUERYPROC endQuery = nullptr;

  TimerCallCounter() {
    // Resolves the entry points first: libepoxy's resolving stubs call through the pointer.
    GLuint query = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &query);
    glBeginQuery(GL_TIME_ELAPSED, query);
    glEndQuery(GL_TIME_ELAPSED);
    glDeleteQueries(1, &query);
    glFinish();
    count = 0;
    finish = epoxy_glFinish;
    createQueries = epoxy_glCreateQueries;
    beginQuery = epoxy_glBeginQuery;
    endQuery = epoxy_glEndQuery;
    epoxy_glFinish = [] {
      ++count;
      finish();
    };
    epoxy_glCreateQueries = [](GLenum target, GLsizei n, GLuint* ids) {
      ++count;
      createQueries(target, n, ids);
    };
    epoxy_glBeginQuery = [](GLenum target, GLuint id) {
      ++count;
      beginQuery(target, id);
    };
    epoxy_glEndQuery = [](GLenum target) {
      ++count;
      endQuery(target);
    };
  }
  ~TimerCallCounter() {
    epoxy_glFinish = finish;
    epoxy_glCreateQueries = createQueries;
    epoxy_glBeginQuery = beginQuery;
    epoxy_glEndQuery = endQuery;
  }
};

TEST_F(GpuTiming, DisabledTimerMakesNoGlCallAndReadsZero) {
  const TimerCallCounter counter;
  gl::GpuTimer timer;
  timer.setEnabled(false);
  timer.begin();
  timer.end();
  EXPECT_EQ(TimerCallCounter::count, 0);
  EXPECT_EQ(timer.wallMilliseconds(), 0.0);
  EXPECT_EQ(timer.gpuMilliseconds(), 0.0);
}

TEST_F(GpuTiming, EnabledTimerFinishesAndQueries) {
  const TimerCallCounter counter;
  gl::GpuTimer timer;
  EXPECT_TRUE(timer.enabled());
  EXPECT_EQ(TimerCallCounter::count, 0);  // the query is made on first use
  timer.begin();
  timer.end();
  EXPECT_EQ(TimerCallCounter::count, 5);  // create, finish, begin, end, finish
  EXPECT_GE(timer.wallMilliseconds(), 0.0);
  EXPECT_GE(timer.gpuMilliseconds(), 0.0);
  timer.setEnabled(false);
  EXPECT_EQ(timer.wallMilliseconds(), 0.0);
  EXPECT_EQ(timer.gpuMilliseconds(), 0.0);
}

TEST_F(GpuTiming, SpanBegunWhileEnabledStillEnds) {
  gl::GpuTimer timer;
  timer.begin();
  timer.setEnabled(false);
  timer.end();  // the query must not stay active
  GLint active = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_CURRENT_QUERY, &active);
  EXPECT_EQ(active, 0);
}

}  // namespace
}  // namespace penumbra
