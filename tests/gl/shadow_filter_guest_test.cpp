// ShadowFilter as a guest on a host's context (CurrentContext, GlErrors::LeaveToHost): a frame's
// filter() waits for nothing — no glFinish, read-back, query result or glGetError — and the
// host's debug callback and pending error survive it. LVSM's Lloyd placement, which reads its
// sums back each step (thesis §4.1.2), is the documented exception.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <bit>

#include "gl_call_swap.h"
#include "gl_test_context.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/program.h"
#include "penumbra/gl/shadow_filter.h"

namespace penumbra::gl {
namespace {

using penumbra::testing::CountedGlCalls;
using penumbra::testing::GlTest;

// Resolves the entry points that wait for the GPU or read its results, then counts their calls.
struct WaitCounter {
  static inline int waits = 0;

  static int resolve() {
    Texture texture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), 1, GL_R32F, 1, 1);
    float texel = 0.0f;
    glGetTextureImage(texture.id(), 0, GL_RED, GL_FLOAT, sizeof texel, &texel);
    Buffer buffer(16);
    glGetNamedBufferSubData(buffer.id(), 0, 4, &texel);
    glReadPixels(0, 0, 0, 0, GL_RED, GL_FLOAT, &texel);
    GLuint query = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &query);
    glBeginQuery(GL_TIME_ELAPSED, query);
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 result = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &result);
    glDeleteQueries(1, &query);
    glFinish();
    while (glGetError() != GL_NO_ERROR) {
    }
    waits = 0;
    return 0;
  }

  int resolved = resolve();
  CountedGlCalls<&epoxy_glFinish> finish{waits};
  CountedGlCalls<&epoxy_glGetError> getError{waits};
  CountedGlCalls<&epoxy_glGetTextureImage> getTextureImage{waits};
  CountedGlCalls<&epoxy_glGetNamedBufferSubData> getNamedBufferSubData{waits};
  CountedGlCalls<&epoxy_glReadPixels> readPixels{waits};
  CountedGlCalls<&epoxy_glGetQueryObjectui64v> getQueryObject{waits};
};

struct HostDebugLog {
  int messages = 0;
};

void GLAPIENTRY hostCallback(GLenum, GLenum, GLuint, GLenum, GLsizei, const GLchar*,
                             const void* user) {
  ++static_cast<HostDebugLog*>(const_cast<void*>(user))->messages;
}

// A host's depth map: an orthographic light's D24 window depth, a step across the middle.
Texture hostDepthMap(int n) {
  Texture depth(GL_TEXTURE_2D);
  glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT24, n, n);
  std::vector<float> values(size_t(n) * size_t(n));
  for (int i = 0; i < n * n; ++i) values[size_t(i)] = (i % n) < n / 2 ? 0.25f : 0.75f;
  glTextureSubImage2D(depth.id(), 0, 0, 0, n, n, GL_DEPTH_COMPONENT, GL_FLOAT, values.data());
  return depth;
}

TEST_F(GlTest, ShadowFilterAsGuestWaitsForNothingAndLeavesTheHostsErrors) {
  static HostDebugLog log;  // outlives the context, which may call back until it goes
  glDebugMessageCallback(hostCallback, &log);
  const Texture depth = hostDepthMap(64);
  const CurrentContext host;  // GlErrors::LeaveToHost: the host's context
  ShadowFilter filter;
  DepthInput input;
  input.texture = depth.id();
  input.size = 64;
  struct Case {
    Technique technique;
    FilterMode mode;
  };
  // Warm every program first: compiling checks its own status (not a wait on the GPU's work,
  // and once per program), and the point is a frame's cost.
  const Case cases[] = {{Technique::Vsm, FilterMode::Trilinear},
                        {Technique::Evsm4, FilterMode::Anisotropic},
                        {Technique::Esm, FilterMode::Bilinear},
                        {Technique::Msm, FilterMode::SummedArea},
                        {Technique::PowerCdf, FilterMode::Trilinear},
                        {Technique::Pcf, FilterMode::Bilinear}};
  auto settingsFor = [](const Case& c) {
    FilterSettings s;
    s.technique = c.technique;
    s.filter = c.mode;
    s.params.esm.classifier = shaders::kEsmClassifyZmax;
    return s;
  };
  for (const Case& c : cases) filter.filter(input, settingsFor(c));
  {
    const WaitCounter counter;  // resolving its entry points drains the queue: the error after
    glEnable(0xFFFF);            // the host's own mistake, pending: GL_INVALID_ENUM
    for (const Case& c : cases) {
      SCOPED_TRACE(std::string(techniqueId(c.technique)));
      filter.filter(input, settingsFor(c));
      filter.bind();
      EXPECT_EQ(WaitCounter::waits, 0);
    }
  }
  void* callback = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
  EXPECT_EQ(std::bit_cast<GLDEBUGPROC>(callback), &hostCallback);
  void* user = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
  EXPECT_EQ(user, &log);
  EXPECT_EQ(glGetError(), GLenum(GL_INVALID_ENUM));  // still the host's to read
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));      // and penumbra made none of its own
}

TEST_F(GlTest, ShadowFilterTimesOnlyWhenAsked) {
  const Texture depth = hostDepthMap(64);
  ShadowFilter filter;
  DepthInput input;
  input.texture = depth.id();
  input.size = 64;
  FilterSettings settings;
  settings.technique = Technique::Vsm;
  settings.filter = FilterMode::Trilinear;
  settings.fusePrefilter = false;
  filter.filter(input, settings);
  EXPECT_EQ(filter.lastTimes().total(), 0.0);
  filter.setTiming(true);
  filter.filter(input, settings);
  const FilterTimes t = filter.lastTimes();
  // Wall clock between glFinish calls: every stage that ran takes some time.
  EXPECT_GT(t.import, 0.0);
  EXPECT_GT(t.encode, 0.0);
  EXPECT_GT(t.prefilter, 0.0);
  EXPECT_GT(t.mipsOrSat, 0.0);
}

}  // namespace
}  // namespace penumbra::gl
