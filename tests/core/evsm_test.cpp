// EVSM (thesis §4.2): the minimum of the two warped bounds, less bleeding than VSM, exponents
// clamped to the storage format.
#include <gtest/gtest.h>

#include <random>

#include "penumbra/depth_distribution.h"
#include "region_helpers.h"
#include "shared/evsm.h"

namespace penumbra {
namespace {

using testing::float32Params;

TEST(Evsm, FourChannelIsAtMostEachSingleBound) {
  TechniqueParams params = float32Params();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> depth(0.0f, 1.0f);
  for (int i = 0; i < 500; ++i) {
    const std::vector<DepthSample> region{
        {depth(rng), 0.3f}, {depth(rng), 0.3f}, {depth(rng), 0.4f}};
    const float receiver = depth(rng);
    const std::vector<float> m = filterRegion(Technique::Evsm4, params, region);
    const float both =
        shaders::evsm4Visibility(glm::vec4(m[0], m[1], m[2], m[3]), receiver, params.evsm);
    const float positive =
        shaders::evsmPositiveVisibility(glm::vec2(m[0], m[1]), receiver, params.evsm);
    const float negative =
        shaders::evsmNegativeVisibility(glm::vec2(m[2], m[3]), receiver, params.evsm);
    EXPECT_LE(both, positive);
    EXPECT_LE(both, negative);
  }
}

TEST(Evsm, BleedsLessThanVsmInTheThreeObjectCase) {
  TechniqueParams params = float32Params();
  const std::vector<DepthSample> region{{0.2f, 0.5f}, {0.3f, 0.5f}};
  for (float c : {0.4f, 0.6f, 0.9f}) {
    const float vsm = evaluateOnRegion(Technique::Vsm, params, region, c);
    const float evsm4 = evaluateOnRegion(Technique::Evsm4, params, region, c);
    const float evsm2 = evaluateOnRegion(Technique::Evsm2, params, region, c);
    EXPECT_LT(evsm4, 0.1f * vsm) << "receiver " << c;
    EXPECT_LE(evsm4, evsm2 + 1e-6f);
  }
}

TEST(Evsm, ExponentIsClampedToWhatTheStorageHolds) {
  shaders::EvsmParams p = shaders::evsmDefaultParams();
  p.positiveExponent = 40.0f;
  p.storage = shaders::kStorageFloat16;
  EXPECT_FLOAT_EQ(shaders::evsmClampExponent(p.positiveExponent, p.storage), 5.54f);
  const glm::vec4 atFar = shaders::evsmEncode(1.0f, p);
  EXPECT_LE(atFar.y, 65504.0f) << "second moment must fit fp16";
  p.storage = shaders::kStorageFloat32;
  p.positiveExponent = 42.0f;
  const glm::vec4 atFar32 = shaders::evsmEncode(1.0f, p);
  EXPECT_TRUE(std::isfinite(atFar32.y));
  EXPECT_LT(atFar32.y, 3.4e38f);
}

TEST(Evsm, DistantReceiversAreNotFlooredByTheVarianceClamp) {
  TechniqueParams params = float32Params();
  const std::vector<DepthSample> region{{0.3f, 0.5f}, {0.5f, 0.5f}};
  EXPECT_LT(evaluateOnRegion(Technique::Evsm4, params, region, 0.9f), 1e-4f);
}

}  // namespace
}  // namespace penumbra
