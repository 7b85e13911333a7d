// ShadowFilter as a guest on a host's context (CurrentContext, GlErrors::LeaveToHost): a frame's
// filter() waits for nothing — no glFinish, read-back, query result or glGetError — and the
// host's debug callback and pending error survive it. LVSM's Lloyd placement (thesis §4.1.2)
// included: it runs on the GPU, and only params() reads its splits back.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <bit>

#include "gl_test_context.h"
#include "gl_wait_counter.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/program.h"
#include "penumbra/gl/shadow_filter.h"
#include "penumbra/shared/layer_placement.h"
#include "penumbra/shared/technique_dispatch.h"

namespace penumbra::gl {
namespace {

using penumbra::testing::GlTest;
using penumbra::testing::WaitCounter;

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
  const Case cases[] = {
      {Technique::Vsm, FilterMode::Trilinear},      {Technique::Evsm4, FilterMode::Anisotropic},
      {Technique::Esm, FilterMode::Bilinear},       {Technique::Msm, FilterMode::SummedArea},
      {Technique::PowerCdf, FilterMode::Trilinear}, {Technique::Pcf, FilterMode::Bilinear},
      {Technique::Lvsm, FilterMode::Trilinear}};
  auto settingsFor = [](const Case& c) {
    FilterSettings s;
    s.technique = c.technique;
    s.filter = c.mode;
    s.params.esm.classifier = shaders::kEsmClassifyZmax;
    s.params.lvsm.placement = shaders::kLayerPlacementLloyd;
    return s;
  };
  for (const Case& c : cases) filter.filter(input, settingsFor(c));
  {
    const WaitCounter counter;  // resolving its entry points drains the queue: the error after
    glEnable(0xFFFF);           // the host's own mistake, pending: GL_INVALID_ENUM
    for (const Case& c : cases) {
      SCOPED_TRACE(std::string(techniqueId(c.technique)));
      filter.filter(input, settingsFor(c));
      filter.bind();
      EXPECT_EQ(WaitCounter::waits, 0);
      EXPECT_EQ(WaitCounter::errorChecks, 0);
    }
    // The last filter was LVSM's: params() reads the placed splits back, once. Every weighted
    // 2x2 block straddles the step (0.25 | 0.75), its second occluder at 0.75: one split moves
    // there, the others are teleported there or, with no weight left, keep their places; the
    // packing keeps them two overlaps apart behind the first, and the placement moves all one
    // overlap in front.
    const TechniqueParams& placed = filter.params();
    EXPECT_EQ(WaitCounter::waits, 1);
    const shaders::LayerSplits& splits = placed.lvsm.splits;
    const float overlap = placed.lvsm.overlap;
    for (int i = 1; i < splits.layerCount; ++i) {
      // D24 holds 0.75 exactly; the rest is fp32 rounding of a few sums.
      EXPECT_NEAR(shaders::layerSplit(splits, i),
                  0.75f - overlap + float(i - 1) * shaders::lloydMinGap(overlap), 1e-5f)
          << i;
    }
    filter.params();
    EXPECT_EQ(WaitCounter::waits, 1) << "read back once";
  }
  {
    // The blocks bind() hands the host hold the placed splits and the encode's ranges for them,
    // as the CPU computes them from those splits (the same shared functions; subtractions and
    // clamps of the same floats: equal to the bit).
    const TechniqueParams& placed = filter.params();
    filter.bind();
    const ShadowBindings bindings;
    GLint parameterBuffer = 0, rangeBuffer = 0;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, GLuint(bindings.parameterBlock), &parameterBuffer);
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, GLuint(bindings.layerRangeBlock), &rangeBuffer);
    TechniqueParams onGpu;
    glGetNamedBufferSubData(GLuint(parameterBuffer), 0, sizeof onGpu, &onGpu);
    shaders::TexelLayerRangeTable ranges;
    glGetNamedBufferSubData(GLuint(rangeBuffer), 0, sizeof ranges, &ranges);
    const shaders::TexelLayerRangeTable expected =
        shaders::texelLayerRangeTable(shaders::kTechniqueLvsm, placed);
    for (int i = 1; i < placed.lvsm.splits.layerCount; ++i) {
      EXPECT_EQ(shaders::layerSplit(onGpu.lvsm.splits, i),
                shaders::layerSplit(placed.lvsm.splits, i));
    }
    for (int t = 0; t < shaders::kMaxTexelLayers; ++t) {
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(ranges.texelLayer[t][c], expected.texelLayer[t][c]) << t;
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
