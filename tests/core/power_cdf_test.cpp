// Power-function CDF (Gumbau et al. 2011): eq. 3's beta, eq. 4's visibility, lit at the mean,
// no bleeding where VSM bleeds, and the layered variant.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/depth_distribution.h"
#include "penumbra/params.h"
#include "region_helpers.h"
#include "penumbra/shared/power_cdf.h"

namespace penumbra {
namespace {

using testing::float32Params;
using testing::visibility;

TEST(PowerCdf, BetaMakesTheFittedCdfMatchTheMean) {
  const float lo = 0.2f, hi = 0.6f;
  for (float mean : {0.25f, 0.3f, 0.4f, 0.55f}) {
    const float beta = shaders::powerCdfBeta(lo, hi, mean);
    EXPECT_NEAR(beta, (mean - lo) / (hi - mean), 1e-6f);  // eq. 3
    // The mean of F(z) = t^beta over [lo, hi] is beta/(beta+1) * (hi - lo) + lo.
    EXPECT_NEAR(beta / (beta + 1.0f) * (hi - lo) + lo, mean, 1e-6f);
  }
}

TEST(PowerCdf, VisibilityFollowsEquation4) {
  const float lo = 0.2f, hi = 0.6f, mean = 0.3f;
  const double beta = (0.3 - 0.2) / (0.6 - 0.3);
  for (float receiver : {0.35f, 0.5f, 0.59f}) {
    const double t = (receiver - 0.2) / 0.4;
    const double expected = (1.0 - std::pow(t, beta)) / (1.0 - std::pow(beta / (beta + 1.0), beta));
    EXPECT_NEAR(shaders::powerCdfVisibilityFromStats(glm::vec3(lo, hi, mean), receiver), expected,
                2e-6);
  }
  EXPECT_EQ(shaders::powerCdfVisibilityFromStats(glm::vec3(lo, hi, mean), 0.6f), 0.0f);
  EXPECT_EQ(shaders::powerCdfVisibilityFromStats(glm::vec3(lo, hi, mean), 0.7f), 0.0f);
}

TEST(PowerCdf, APlanarReceiverAtTheMeanIsLit) {
  const TechniqueParams params = float32Params();
  // A tilted planar receiver: depths spread symmetrically about the pixel's own depth.
  const std::vector<DepthSample> slope{
      {0.48f, 0.25f}, {0.49f, 0.25f}, {0.51f, 0.25f}, {0.52f, 0.25f}};
  EXPECT_EQ(evaluateOnRegion(Technique::PowerCdf, params, slope, 0.5f), 1.0f);
}

TEST(PowerCdf, DoesNotBleedWhereVsmBleeds) {
  const TechniqueParams params = float32Params();
  const std::vector<DepthSample> region{{0.2f, 0.5f}, {0.3f, 0.5f}};
  for (float c : {0.4f, 0.6f, 0.9f}) {
    EXPECT_EQ(evaluateOnRegion(Technique::PowerCdf, params, region, c), 0.0f);
    EXPECT_GT(evaluateOnRegion(Technique::Vsm, params, region, c), 0.005f);
  }
}

TEST(PowerCdf, LayeredVariantSeparatesOccluderGroups) {
  TechniqueParams params = float32Params();
  // A near and a far occluder; the receiver lies just in front of the far one. One power
  // function cannot fit the gap between them; a split between them fits each group alone.
  const std::vector<DepthSample> region{{0.1f, 0.5f}, {0.7f, 0.5f}};
  const float receiver = 0.65f;
  const float exact = exactVisibility(region, receiver);
  const float single = evaluateOnRegion(Technique::PowerCdf, params, region, receiver);
  setParam(Technique::PowerCdf, params, "splits", "0.5");
  const float layered = evaluateOnRegion(Technique::PowerCdf, params, region, receiver);
  EXPECT_FLOAT_EQ(exact, 0.5f);
  EXPECT_GT(std::abs(single - exact), 0.3f);  // beta = 1, t = 11/12: (1 - t) / (1/2) = 1/6
  // Clamped to the layer [0.5 - overlap, 1] = [0.49, 1]: min 0.49, mean 0.595, max 0.7, so
  // beta = 1, t = 0.16 / 0.21 = 16/21 and (1 - t) / (1/2) = 10/21. fp32 rounding: 1e-5.
  EXPECT_NEAR(layered, 10.0f / 21.0f, 1e-5f);
  setParam(Technique::PowerCdf, params, "overlap", "0");
  // Without overlap the layer is [0.5, 1]: beta = 1, t = 3/4: exactly the 1/2 of PCF.
  EXPECT_NEAR(evaluateOnRegion(Technique::PowerCdf, params, region, receiver), exact, 1e-5f);
  EXPECT_EQ(channelCount(Technique::PowerCdf, params), 6);
}

TEST(PowerCdf, LayerOverlapKeepsASlopedReceiverBelowASplitLit) {
  // A lit receiver whose filter region spans +-0.01 of its own sloped surface, 0.0005 below the
  // split at 0.5 (review item 3). One layer: the receiver sits at the region's mean, lit.
  TechniqueParams params = float32Params();
  std::vector<DepthSample> ownSurface;
  for (int i = 0; i < 21; ++i) ownSurface.push_back({0.4895f + 0.001f * float(i), 1.0f / 21.0f});
  const float receiver = 0.4995f;
  EXPECT_EQ(evaluateOnRegion(Technique::PowerCdf, params, ownSurface, receiver), 1.0f);
  setParam(Technique::PowerCdf, params, "splits", "0.5");
  // The default overlap (0.01) keeps the surface inside the receiver's layer: still lit.
  EXPECT_EQ(evaluateOnRegion(Technique::PowerCdf, params, ownSurface, receiver), 1.0f);
  // Without it the far half is clamped onto the split and the receiver darkens (about 0.6).
  setParam(Technique::PowerCdf, params, "overlap", "0");
  EXPECT_LT(evaluateOnRegion(Technique::PowerCdf, params, ownSurface, receiver), 0.75f);
}

TEST(PowerCdf, SixteenBitStorageStaysCloseToThirtyTwo) {
  TechniqueParams p32 = float32Params();
  TechniqueParams p16 = p32;
  p16.powerCdf.storage = shaders::kStorageFloat16;
  const std::vector<DepthSample> occluders{{0.3f, 0.3f}, {0.45f, 0.2f}};
  for (float receiver : {0.35f, 0.5f, 0.7f}) {
    EXPECT_NEAR(visibility(Technique::PowerCdf, p16, occluders, receiver),
                visibility(Technique::PowerCdf, p32, occluders, receiver), 0.02f);
  }
}

}  // namespace
}  // namespace penumbra
