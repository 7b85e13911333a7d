// PCF kernels (thesis ch. 2): normalised weights, the bilinear-weighted kernel's tent ends, and
// the biased depth test.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/shared/pcf.h"

namespace penumbra {
namespace {

float weightSum(const shaders::PcfParams& p, glm::vec2 fraction) {
  float sum = 0.0f;
  for (int y = shaders::pcfFirstTap(p); y <= shaders::pcfLastTap(p); ++y) {
    for (int x = shaders::pcfFirstTap(p); x <= shaders::pcfLastTap(p); ++x) {
      sum += shaders::pcfTapWeight(x, y, fraction, p);
    }
  }
  return sum;
}

TEST(Pcf, EveryKernelsWeightsSumToOne) {
  shaders::PcfParams p = shaders::pcfDefaultParams();
  for (int kernel : {shaders::kKernelBox, shaders::kKernelGaussian, shaders::kKernelBilinear,
                     shaders::kKernelGaussianBilinear}) {
    for (int radius : {0, 1, 2, 7}) {
      for (glm::vec2 f : {glm::vec2(0.0f), glm::vec2(0.3f, 0.8f), glm::vec2(0.999f, 0.5f)}) {
        p.kernel = kernel;
        p.radius = radius;
        p.sigma = 1.5f;
        EXPECT_NEAR(weightSum(p, f), 1.0f, 1e-5f) << kernel << " r" << radius;
      }
    }
  }
}

TEST(Pcf, BilinearKernelOfRadiusZeroIsBilinearInterpolation) {
  shaders::PcfParams p = shaders::pcfDefaultParams();
  p.kernel = shaders::kKernelBilinear;
  p.radius = 0;
  const glm::vec2 f(0.25f, 0.75f);
  EXPECT_FLOAT_EQ(shaders::pcfTapWeight(0, 0, f, p), 0.75f * 0.25f);
  EXPECT_FLOAT_EQ(shaders::pcfTapWeight(1, 0, f, p), 0.25f * 0.25f);
  EXPECT_FLOAT_EQ(shaders::pcfTapWeight(0, 1, f, p), 0.75f * 0.75f);
  EXPECT_FLOAT_EQ(shaders::pcfTapWeight(1, 1, f, p), 0.25f * 0.75f);
}

TEST(Pcf, BilinearKernelTapersOnlyItsEndTaps) {
  shaders::PcfParams p = shaders::pcfDefaultParams();
  p.kernel = shaders::kKernelBilinear;
  p.radius = 2;
  const glm::vec2 f(0.4f, 0.0f);
  EXPECT_FLOAT_EQ(shaders::kernelWeight1D(p.kernel, -2, 2, 1.0f, 0.4f), 0.6f / 5.0f);
  EXPECT_FLOAT_EQ(shaders::kernelWeight1D(p.kernel, 0, 2, 1.0f, 0.4f), 1.0f / 5.0f);
  EXPECT_FLOAT_EQ(shaders::kernelWeight1D(p.kernel, 3, 2, 1.0f, 0.4f), 0.4f / 5.0f);
  EXPECT_EQ(shaders::kernelWeight1D(p.kernel, 4, 2, 1.0f, 0.4f), 0.0f);
  EXPECT_EQ(shaders::pcfTapWeight(0, 3, f, p), 0.0f);  // fraction 0: the far end tap is unused
}

TEST(Pcf, GaussianWeightsFollowTheBellCurve) {
  const float centre = shaders::kernelWeight1D(shaders::kKernelGaussian, 0, 3, 1.0f, 0.0f);
  const float one = shaders::kernelWeight1D(shaders::kKernelGaussian, 1, 3, 1.0f, 0.0f);
  EXPECT_NEAR(one / centre, std::exp(-0.5f), 1e-6f);
  EXPECT_EQ(shaders::kernelWeight1D(shaders::kKernelGaussian, 4, 3, 1.0f, 0.0f), 0.0f);
}

TEST(Pcf, DepthTestIsBiasedTowardTheLight) {
  shaders::HardParams bias = shaders::hardDefaultParams();
  bias.constantBias = 0.01f;
  bias.slopeScaledBias = 2.0f;
  EXPECT_FLOAT_EQ(shaders::biasedReceiverDepth(0.5f, 0.005f, bias), 0.5f - 0.01f - 0.01f);
  EXPECT_EQ(shaders::hardVisibility(0.49f, shaders::biasedReceiverDepth(0.5f, 0.0f, bias)), 1.0f);
  EXPECT_EQ(shaders::hardVisibility(0.48f, shaders::biasedReceiverDepth(0.5f, 0.0f, bias)), 0.0f);
}

}  // namespace
}  // namespace penumbra
