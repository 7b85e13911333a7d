// GpuTimer's switch: a disabled timer makes no GL call (no glFinish stalls a host's frame, no
// query) and reads 0; an enabled one, the default, times as before.
#include "gpu_timer.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl_call_swap.h"
#include "gl_test_context.h"

namespace penumbra {
namespace {

class GpuTiming : public testing::GlTest {};

// Counts the calls a timer makes (tests/gl/gl_call_swap.h), its entry points resolved first.
struct TimerCallCounter {
  static inline int count = 0;

  static int resolve() {
    GLuint query = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &query);
    glBeginQuery(GL_TIME_ELAPSED, query);
    glEndQuery(GL_TIME_ELAPSED);
    glDeleteQueries(1, &query);
    glFinish();
    count = 0;
    return 0;
  }

  int resolved = resolve();
  testing::CountedGlCalls<&epoxy_glFinish> finish{count};
  testing::CountedGlCalls<&epoxy_glCreateQueries> createQueries{count};
  testing::CountedGlCalls<&epoxy_glBeginQuery> beginQuery{count};
  testing::CountedGlCalls<&epoxy_glEndQuery> endQuery{count};
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
