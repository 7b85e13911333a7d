// VSM against the thesis: exact for a planar occluder over a planar receiver (§3.2), the
// three-object light-bleeding value (eq. 3.4), and bleeding reduction (§3.4).
#include <gtest/gtest.h>

#include "penumbra/depth_distribution.h"
#include "region_helpers.h"
#include "penumbra/shared/vsm.h"

namespace penumbra {
namespace {

using testing::float32Params;
using testing::visibility;

TEST(Vsm, IsExactForPlanarOccluderAndReceiver) {
  TechniqueParams params = float32Params();
  params.vsm.minVariance = 0.0f;
  for (float occluded : {0.1f, 0.25f, 0.5f, 0.75f, 0.9f}) {
    for (float gap : {0.05f, 0.2f, 0.5f}) {
      const float occluder = 0.2f;
      const float receiver = occluder + gap;
      const std::vector<DepthSample> occluders{{occluder, occluded}};
      const float pcf = visibility(Technique::Pcf, params, occluders, receiver);
      const float vsm = visibility(Technique::Vsm, params, occluders, receiver);
      EXPECT_NEAR(pcf, 1.0f - occluded, 1e-6f);
      EXPECT_NEAR(vsm, pcf, 2e-5f) << "occluded share " << occluded << ", gap " << gap;
    }
  }
}

TEST(Vsm, BleedsAsThesisEquation3_4InTheThreeObjectCase) {
  TechniqueParams params = float32Params();
  params.vsm.minVariance = 0.0f;
  const float a = 0.2f, b = 0.3f;
  const std::vector<DepthSample> region{{a, 0.5f}, {b, 0.5f}};
  for (float c : {0.35f, 0.5f, 0.8f}) {
    const double dx = b - a, dy = c - b;
    const double expected = 0.25 * dx * dx / (0.5 * dx * dx + dx * dy + dy * dy);
    const float vsm = evaluateOnRegion(Technique::Vsm, params, region, c);
    EXPECT_NEAR(vsm, expected, 1e-5) << "receiver C at " << c;
    EXPECT_EQ(exactVisibility(region, c), 0.0f);
    EXPECT_GT(vsm, 0.005f) << "VSM should bleed light onto C";
  }
}

TEST(Vsm, BleedingReductionClampsTheTailAndRescales) {
  const float pMax = 0.4f;
  EXPECT_FLOAT_EQ(shaders::reduceLightBleeding(pMax, 0.0f), pMax);
  EXPECT_FLOAT_EQ(shaders::reduceLightBleeding(pMax, 0.5f), 0.0f);
  EXPECT_NEAR(shaders::reduceLightBleeding(pMax, 0.2f), (0.4f - 0.2f) / 0.8f, 1e-6f);
  EXPECT_FLOAT_EQ(shaders::reduceLightBleeding(1.0f, 0.3f), 1.0f);
}

TEST(Vsm, MinVarianceFloorsTheVariance) {
  const glm::vec2 singleDepth = shaders::vsmEncode(0.5f);
  EXPECT_FLOAT_EQ(shaders::chebyshevUpperBound(singleDepth, 0.6f, 0.0f), 0.0f);
  const float withFloor = shaders::chebyshevUpperBound(singleDepth, 0.6f, 0.01f);
  EXPECT_NEAR(withFloor, 0.01f / (0.01f + 0.01f), 1e-6f);
}

}  // namespace
}  // namespace penumbra
