// The fused prefilter (encode and both blur axes in one dispatch over a shared-memory tile) gives
// the separate passes' channels: the same taps, order and fp32 arithmetic, with the tile's border
// clamped at the map's edges as the separate passes clamp each tap. Map sizes that are and are
// not multiples of the 16-texel tile, kernels from one texel to the largest the tile holds.
#include <gtest/gtest.h>

#include <cmath>

#include "gl_test_context.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/params.h"

namespace penumbra {
namespace {

class FusedPrefilter : public testing::GlTest {};

// The fused path is opt-in (RenderSettings::fusePrefilter: on llvmpipe it took several times the
// separate passes' time, docs/renderer.md): default settings run the separate passes even where
// the fused one applies, which asking for it shows.
TEST_F(FusedPrefilter, IsOffByDefault) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("planar");
  gl::RenderSettings s;
  s.shadowMapSize = 64;
  s.width = 32;
  s.height = 18;
  EXPECT_FALSE(renderer.render(scene, s).fusedPrefilter);
  s.fusePrefilter = true;
  EXPECT_TRUE(renderer.render(scene, s).fusedPrefilter);
}

TEST_F(FusedPrefilter, GivesTheSeparatePassesChannels) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("backyard");
  struct Case {
    Technique technique;
    const char* param;  // on top of the defaults, or nullptr
  };
  // Every reduction the fused path meets: means (VSM, EVSM4, LVSM's layers), ESM's log-space
  // mean and linear mean, the power CDF's min and max, several texel layers.
  const Case cases[] = {{Technique::Vsm, nullptr},           {Technique::Evsm4, nullptr},
                        {Technique::Esm, "filtering=log"},   {Technique::Esm, "filtering=linear"},
                        {Technique::PowerCdf, "layers=3"},   {Technique::Csm, "storage=float32"},
                        {Technique::Lvsm, "storage=float32"}};
  for (const Case& k : cases) {
    for (const int size : {96, 100}) {
      // 10: kMaxFusedBlurRadius. A Gaussian weighs each tap, a box sums its taps and scales
      // once (shared/channel_reduction.h scaleTapWeights).
      for (const BlurSpec blur :
           {BlurSpec{BlurKernel::Gaussian, 1, 0.5f}, BlurSpec{BlurKernel::Gaussian, 10, 5.0f},
            BlurSpec{BlurKernel::Box, 1, 1.0f}, BlurSpec{BlurKernel::Box, 10, 1.0f}}) {
        gl::RenderSettings s;
        s.technique = k.technique;
        if (k.param != nullptr) {
          const std::vector<Technique> one{k.technique};
          applyParamAssignment(one, s.params, k.param);
        }
        s.shadowMapSize = size;
        s.width = 32;
        s.height = 18;
        s.filter = gl::FilterMode::Bilinear;
        s.blur = blur;
        s.fusePrefilter = true;  // the path under test, off by default
        const std::string what = std::string(techniqueId(k.technique)) + " " +
                                 (k.param ? k.param : "") + " " + std::to_string(size) + "^2 " +
                                 (blur.kernel == BlurKernel::Box ? "box" : "gaussian") +
                                 " radius " + std::to_string(blur.radius);
        const gl::RenderResult fused = renderer.render(scene, s);
        ASSERT_TRUE(fused.fusedPrefilter) << what;
        ASSERT_EQ(fused.memory.scratch, 0u) << what;  // one map fused needs no scratch texture
        const Image fusedChannels = renderer.readChannels(0);
        s.fusePrefilter = false;
        const gl::RenderResult separate = renderer.render(scene, s);
        ASSERT_FALSE(separate.fusedPrefilter) << what;
        ASSERT_GT(separate.memory.scratch, 0u) << what;
        const Image separateChannels = renderer.readChannels(0);
        ASSERT_EQ(fusedChannels.data().size(), separateChannels.data().size());
        int bad = 0;
        for (size_t i = 0; i < fusedChannels.data().size(); ++i) {
          const float a = fusedChannels.data()[i], b = separateChannels.data()[i];
          // Same arithmetic in the same order, the encode and the taps' sums precise in both
          // (shared/technique_dispatch.h, channel_reduction.h): the same bits.
          if (!(a == b) && ++bad <= 3) {
            ADD_FAILURE() << what << " value " << i << " (texel "
                          << i / size_t(fusedChannels.channels()) << "): fused " << a
                          << " separate " << b;
          }
        }
        EXPECT_EQ(bad, 0) << what;
      }
    }
  }
}

// Cascades fuse when every cascade's kernel does (each its own kernel, scaled to the same world
// width; here radii 3, 1 and 0, the last encode only): three cascades of VSM give the separate
// passes' channels in every cascade.
TEST_F(FusedPrefilter, GivesTheSeparatePassesChannelsInEveryCascade) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("street");
  gl::RenderSettings s;
  s.technique = Technique::Vsm;
  s.shadowMapSize = 96;
  s.width = 64;
  s.height = 36;
  s.filter = gl::FilterMode::Bilinear;
  s.blur = {BlurKernel::Box, 3, 1.0f};
  s.cascades.count = 3;
  s.fusePrefilter = true;
  const gl::RenderResult fused = renderer.render(scene, s);
  ASSERT_EQ(fused.cascadeBlurs.size(), 3u);
  ASSERT_TRUE(fused.fusedPrefilter)
      << fused.cascadeBlurs[0].radius << " " << fused.cascadeBlurs[1].radius << " "
      << fused.cascadeBlurs[2].radius;
  std::vector<Image> fusedChannels;
  for (int c = 0; c < 3; ++c) fusedChannels.push_back(renderer.readChannels(0, c));
  s.fusePrefilter = false;
  const gl::RenderResult separate = renderer.render(scene, s);
  ASSERT_FALSE(separate.fusedPrefilter);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(fused.cascadeBlurs[size_t(c)].radius, separate.cascadeBlurs[size_t(c)].radius);
    const Image channels = renderer.readChannels(0, c);
    int bad = 0;
    for (size_t i = 0; i < channels.data().size(); ++i) {
      const float a = fusedChannels[size_t(c)].data()[i], b = channels.data()[i];
      // As above: equal up to fma contraction.
      if (!(std::abs(a - b) <= 1e-6f * std::max(1.0f, std::abs(b))) && ++bad <= 3) {
        ADD_FAILURE() << "cascade " << c << " value " << i << ": fused " << a << " separate " << b;
      }
    }
    EXPECT_EQ(bad, 0) << "cascade " << c;
  }
}

}  // namespace
}  // namespace penumbra
