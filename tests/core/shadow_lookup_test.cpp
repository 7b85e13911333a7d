// The CPU twin of the camera-pass lookup (penumbra/shadow_lookup.h) on hand-built depth maps:
// GL's tap geometry, power-CDF's min/max over the taps, ESM's fallbacks, sub-texel summed-area
// boxes and the exact filtered reference, each against a value derived by hand or by brute force.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/error.h"
#include "penumbra/params.h"
#include "penumbra/shadow_lookup.h"
#include "penumbra/shared/lookup_footprint.h"
#include "penumbra/shared/vsm.h"

namespace penumbra {
namespace {

// A square depth map: `left` where x < split, `right` elsewhere.
Image stepDepth(int size, int split, float left, float right) {
  Image depth(size, size, 1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) depth.at(x, y) = x < split ? left : right;
  }
  return depth;
}

LookupConfig configFor(Technique technique, FilterMode filter, int blurRadius) {
  LookupConfig config;
  config.technique = technique;
  config.params = defaultTechniqueParams();
  config.filter = filter;
  config.blur = {BlurKernel::Box, blurRadius, 1.0f};
  return config;
}

LookupPixel flatReceiverAt(float texelX, float texelY, int size, float depth) {
  LookupPixel p;
  p.uv = {texelX / float(size), texelY / float(size)};
  p.receiverDepth = depth;
  return p;
}

TEST(LookupFootprint, BilinearTapsFollowGlTexelCentres) {
  // At a texel centre the lookup is that texel alone; halfway between two centres, both halves.
  shaders::BilinearTaps t = shaders::bilinearTaps({2.5f / 4.0f, 1.5f / 2.0f}, 4);
  EXPECT_EQ(t.base, glm::ivec2(2, 2));  // y uses size 4 here: 1.5/2 * 4 - 0.5 = 2.5 -> base 2
  EXPECT_FLOAT_EQ(t.fraction.x, 0.0f);
  EXPECT_FLOAT_EQ(t.fraction.y, 0.5f);
  EXPECT_FLOAT_EQ(shaders::bilinearTapWeight(t, 0, 0), 0.5f);
  EXPECT_FLOAT_EQ(shaders::bilinearTapWeight(t, 1, 1), 0.0f);
  t = shaders::bilinearTaps({0.0f, 0.0f}, 4);  // the corner: taps -1 and 0, clamped to the edge
  EXPECT_EQ(t.base, glm::ivec2(-1, -1));
  EXPECT_EQ(shaders::clampTexel(t.base, 4), glm::ivec2(0, 0));
}

TEST(LookupFootprint, TrilinearBlendsTheTwoLevelsAroundTheLodAndClamps) {
  shaders::TrilinearLevels l = shaders::trilinearLevels(2.25f, 5);
  EXPECT_EQ(l.level, 2);
  EXPECT_EQ(l.next, 3);
  EXPECT_FLOAT_EQ(l.fraction, 0.25f);
  l = shaders::trilinearLevels(-3.0f, 5);  // magnified: level 0 alone
  EXPECT_EQ(l.level, 0);
  EXPECT_FLOAT_EQ(l.fraction, 0.0f);
  l = shaders::trilinearLevels(99.0f, 5);  // beyond the chain: the last level alone
  EXPECT_EQ(l.level, 4);
  EXPECT_FLOAT_EQ(l.fraction, 0.0f);
}

TEST(ShadowLookup, PowerCdfTakesMinAndMaxOverTheLookupsTaps) {
  // Halfway between a texel at 0.2 and one at 0.6 (review item 2): min 0.2, max 0.6, mean 0.4,
  // so beta = 1 and, for the receiver at 0.5 less the 0.001 bias, t = 0.299 / 0.4 = 0.7475:
  // (1 - t) / (1 - 1/2) = 0.505 (Gumbau eq. 4), next to the exact 0.5. Min and max averaged
  // linearly would both be 0.4, a zero range: visibility 0.
  LookupConfig config = configFor(Technique::PowerCdf, FilterMode::Bilinear, 0);
  const CpuShadowLookup lookup(stepDepth(16, 8, 0.2f, 0.6f), config);
  const float v = lookup.lookup(flatReceiverAt(8.0f, 8.5f, 16, 0.5f)).visibility;
  EXPECT_NEAR(v, 0.505f, 1e-4f);  // fp32 through log/exp of eq. 4
}

TEST(ShadowLookup, EsmFallbackFromTheUnfilteredDepthUndoesThePrefilter) {
  // A receiver at 0.5 on the texel x = 14 of an occluder at 0.3 whose 5x5 box blur reaches the
  // far column x = 16 (0.9): exp(80 * 0.9) dominates the filtered ESM, so the threshold test
  // fails (ESM paper §3.3). The fallback PCF of the unfiltered depth with the prefilter's kernel
  // sees one lit column of five: 0.2, the filtered reference. The paper's fallback tests the
  // four nearest *prefiltered* texels, all of which hold that far column: lit (paper §3.4).
  LookupConfig config = configFor(Technique::Esm, FilterMode::Bilinear, 2);
  const Image depth = stepDepth(32, 16, 0.3f, 0.9f);
  const LookupPixel pixel = flatReceiverAt(14.5f, 16.5f, 32, 0.5f);
  const CpuShadowLookup pcfFallback(depth, config);
  const LookupSample pcf = pcfFallback.lookup(pixel);
  EXPECT_EQ(pcf.diagnostic, 1.0f);
  EXPECT_NEAR(pcf.visibility, 0.2f, 1e-6f);
  EXPECT_NEAR(pcf.visibility, pcfFallback.referenceVisibility(pixel), 1e-6f);
  setParam(Technique::Esm, config.params, "fallback", "paper");
  const LookupSample paper = CpuShadowLookup(depth, config).lookup(pixel);
  EXPECT_EQ(paper.diagnostic, 1.0f);
  EXPECT_EQ(paper.visibility, 1.0f);
}

TEST(ShadowLookup, SummedAreaBoxMovesSmoothlyWithTheLookup) {
  // VSM through a summed-area table over a step (0.2 | 0.6 at x = 16); the 5-texel box slides
  // across it in quarter texels (review item 5). The share s of the box beyond the step grows
  // linearly, and so do the moments: M1 = 0.2 + 0.4 s, M2 = 0.04 + 0.32 s. A box snapped to the
  // texel grid would hold s for a whole texel and then jump.
  LookupConfig config = configFor(Technique::Vsm, FilterMode::SummedArea, 2);
  const CpuShadowLookup lookup(stepDepth(32, 16, 0.2f, 0.6f), config);
  for (float centre = 13.75f; centre <= 16.25f; centre += 0.25f) {
    const float s = std::clamp((centre + 2.5f - 16.0f) / 5.0f, 0.0f, 1.0f);
    const LookupPixel pixel = flatReceiverAt(centre, 10.5f, 32, 0.4f);
    const glm::vec2 moments(0.2f + 0.4f * s, 0.04f + 0.32f * s);
    // Fixed-point sums: exact to 2^-32 of the range; fp32 Chebyshev: 1e-5.
    EXPECT_NEAR(lookup.lookup(pixel).visibility,
                shaders::vsmVisibility(moments, 0.4f, config.params.vsm), 1e-5f)
        << "box centre " << centre;
    // The reference over the same box: the lit share.
    EXPECT_NEAR(lookup.referenceVisibility(pixel), s, 1e-6f) << "box centre " << centre;
  }
}

TEST(ShadowLookup, FilteredReferenceIsExactForMipBlocksWiderThanEightTexels) {
  // Trilinear at lod 5: every level-5 texel is the mean of a 32x32 block of box-blurred tests
  // (review item 6). Brute force: all 32x32 x 3x3 tests of each of the four bilinear taps.
  const int size = 64;
  Image depth(size, size, 1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) depth.at(x, y) = ((x * 7 + y * 13) % 5 < 2) ? 0.3f : 0.7f;
  }
  LookupConfig config = configFor(Technique::Vsm, FilterMode::Trilinear, 1);
  const CpuShadowLookup lookup(depth, config);
  LookupPixel pixel;
  pixel.uv = {0.3f, 0.6f};
  pixel.receiverDepth = 0.5f;
  pixel.uvDx = {32.0f / float(size), 0.0f};  // a 32-texel footprint: lod 5
  pixel.uvDy = {0.0f, 32.0f / float(size)};

  auto blurredTest = [&](int bx, int by) {
    double lit = 0.0;
    for (int j = -1; j <= 1; ++j) {
      for (int i = -1; i <= 1; ++i) lit += depth.clamped(bx + i, by + j) >= 0.5f ? 1.0 / 9.0 : 0.0;
    }
    return lit;
  };
  auto levelFiveTexel = [&](int tx, int ty) {
    double sum = 0.0;
    for (int by = 32 * ty; by < 32 * ty + 32; ++by) {
      for (int bx = 32 * tx; bx < 32 * tx + 32; ++bx) sum += blurredTest(bx, by);
    }
    return sum / (32.0 * 32.0);
  };
  // Level 5 is 2x2 texels; position uv * 2 - 0.5 = (0.1, 0.7): taps (0..1, 0..1).
  const double fx = 0.1, fy = 0.7;
  const double expected = (1 - fx) * (1 - fy) * levelFiveTexel(0, 0) +
                          fx * (1 - fy) * levelFiveTexel(1, 0) +
                          (1 - fx) * fy * levelFiveTexel(0, 1) + fx * fy * levelFiveTexel(1, 1);
  // fp32 sums of ~1200 weighted tests: 1e-5.
  EXPECT_NEAR(lookup.referenceVisibility(pixel), expected, 1e-5);
}

TEST(ShadowLookup, MipMappedReferenceRefusesANonPowerOfTwoMap) {
  LookupConfig config;
  config.filter = FilterMode::Trilinear;
  const CpuShadowLookup lookup(stepDepth(48, 24, 0.2f, 0.6f), config);
  EXPECT_THROW(lookup.referenceVisibility(flatReceiverAt(10.5f, 10.5f, 48, 0.4f)), Error);
  config.filter = FilterMode::Bilinear;  // no mips: any size
  EXPECT_NO_THROW(CpuShadowLookup(stepDepth(48, 24, 0.2f, 0.6f), config)
                      .referenceVisibility(flatReceiverAt(10.5f, 10.5f, 48, 0.4f)));
}

TEST(ShadowLookup, FilteredChannelsAreWhatTheReconstructionReads) {
  // MSM, float32, no blur, bilinear: halfway between the texel centres either side of the step,
  // the filtered moments are the mean of the two depths' powers; reconstructing from them is the
  // lookup. PCF filters after the test: no filtered channels.
  LookupConfig config = configFor(Technique::Msm, FilterMode::Bilinear, 0);
  setParam(Technique::Msm, config.params, "storage", "float32");
  const CpuShadowLookup lookup(stepDepth(16, 8, 0.25f, 0.75f), config);
  const LookupPixel pixel = flatReceiverAt(8.0f, 4.5f, 16, 0.5f);
  const std::vector<float> filtered = lookup.filteredChannels(pixel);
  ASSERT_EQ(filtered.size(), 4u);
  const float near[4] = {0.25f, 0.0625f, 0.015625f, 0.00390625f};
  const float far[4] = {0.75f, 0.5625f, 0.421875f, 0.31640625f};
  for (int c = 0; c < 4; ++c) EXPECT_EQ(filtered[size_t(c)], 0.5f * (near[c] + far[c])) << c;
  EXPECT_EQ(reconstructVisibility(Technique::Msm, config.params, filtered, pixel.receiverDepth),
            lookup.lookup(pixel).visibility);
  config.technique = Technique::Pcf;
  EXPECT_TRUE(
      CpuShadowLookup(stepDepth(16, 8, 0.25f, 0.75f), config).filteredChannels(pixel).empty());
}

}  // namespace
}  // namespace penumbra
