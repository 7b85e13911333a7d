// Moment shadow maps (Peters & Klein 2015, shared/papers/msm-notes.md): the quantisation
// matrices, the Hamburger reconstruction on hand-computed cases, bounds and degenerate moments.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/depth_distribution.h"
#include "penumbra/error.h"
#include "penumbra/params.h"
#include "region_helpers.h"
#include "shared/msm.h"

namespace penumbra {
namespace {

using testing::float32Params;

TEST(Msm, QuantisationMatricesAreInverses) {
  const glm::mat4 product = shaders::msmDequantizationMatrix() * shaders::msmQuantizationMatrix();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(product[i][j], i == j ? 1.0f : 0.0f, 2e-5f);
  }
}

TEST(Msm, QuantisedMomentsStayInTheUnitRange) {
  shaders::MsmParams p = shaders::msmDefaultParams();
  for (int i = 0; i <= 1000; ++i) {
    const glm::vec4 q = shaders::msmEncode(float(i) / 1000.0f, p);
    for (int c = 0; c < 4; ++c) {
      EXPECT_GE(q[c], -1e-6f);
      EXPECT_LE(q[c], 1.0f + 1e-6f);
    }
    const glm::vec4 b = shaders::msmDecode(q, p);
    EXPECT_NEAR(b.x, float(i) / 1000.0f, 1e-5f);
  }
}

// Two atoms: a with weight w and b with 1 - w. By hand (notes step 4), the roots are a and b,
// so G = w between them (z2 < zf <= z3 case) and 1 beyond b: exactly what PCF returns.
TEST(Msm, TwoAtomDistributionMatchesTheHandComputedIntensity) {
  TechniqueParams params = float32Params();
  const std::vector<DepthSample> region{{0.2f, 0.3f}, {0.6f, 0.7f}};
  EXPECT_NEAR(evaluateOnRegion(Technique::Msm, params, region, 0.4f), 0.7f, 2e-3f);
  EXPECT_NEAR(evaluateOnRegion(Technique::Msm, params, region, 0.8f), 0.0f, 2e-3f);
  EXPECT_NEAR(evaluateOnRegion(Technique::Msm, params, region, 0.1f), 1.0f, 1e-6f);
}

TEST(Msm, MomentBiasFollowsTheStorageUnlessSetExplicitly) {
  // The notes' alpha: 3e-5 for 16-bit storage, 3e-6 for 32-bit; a value the user gives is kept,
  // whatever the order of the assignments.
  const TechniqueParams defaults = defaultTechniqueParams();
  EXPECT_EQ(formatParam(Technique::Msm, defaults, "momentBias"), "auto");
  EXPECT_EQ(shaders::msmMomentBias(defaults.msm), 3e-5f);
  TechniqueParams p = defaults;
  setParam(Technique::Msm, p, "storage", "float32");
  EXPECT_EQ(shaders::msmMomentBias(p.msm), 3e-6f);
  EXPECT_NO_THROW(validateParams(Technique::Msm, p));
  for (bool biasFirst : {true, false}) {
    TechniqueParams q = defaults;
    if (biasFirst) setParam(Technique::Msm, q, "momentBias", "1e-4");
    setParam(Technique::Msm, q, "storage", "float32");
    if (!biasFirst) setParam(Technique::Msm, q, "momentBias", "1e-4");
    EXPECT_EQ(shaders::msmMomentBias(q.msm), 1e-4f) << biasFirst;
    setParam(Technique::Msm, q, "momentBias", "auto");
    EXPECT_EQ(shaders::msmMomentBias(q.msm), 3e-6f);
  }
  EXPECT_THROW(setParam(Technique::Msm, p, "momentBias", "-1"),
               Error);  // the sentinel is not input

  // The reconstruction uses it: float32 storage by default reconstructs as with 3e-6, not 3e-5.
  TechniqueParams small = p, large = p;
  small.msm.momentBias = 3e-6f;
  large.msm.momentBias = 3e-5f;
  const std::vector<DepthSample> region{{0.2f, 0.3f}, {0.6f, 0.7f}};
  float largestDifference = 0.0f;
  for (float receiver : {0.3f, 0.5f, 0.61f, 0.7f}) {
    const float v = evaluateOnRegion(Technique::Msm, p, region, receiver);
    EXPECT_EQ(v, evaluateOnRegion(Technique::Msm, small, region, receiver)) << receiver;
    largestDifference = std::max(
        largestDifference, std::abs(v - evaluateOnRegion(Technique::Msm, large, region, receiver)));
  }
  EXPECT_GT(largestDifference, 1e-4f);
}

TEST(Msm, SixteenBitOptimisedQuantisationStaysCloseToFloat) {
  TechniqueParams p32 = float32Params();
  TechniqueParams p16 = p32;
  p16.msm.storage = shaders::kStorageUnorm16;
  p16.msm.momentBias = 3e-5f;
  const std::vector<DepthSample> region{{0.2f, 0.3f}, {0.6f, 0.7f}};
  for (float receiver : {0.3f, 0.5f, 0.7f}) {
    EXPECT_NEAR(evaluateOnRegion(Technique::Msm, p16, region, receiver),
                evaluateOnRegion(Technique::Msm, p32, region, receiver), 0.03f);
  }
}

TEST(Msm, DegenerateMomentsGiveBoundedFiniteResults) {
  for (float bias : {3e-6f, 3e-5f}) {
    for (glm::vec4 b : {glm::vec4(0.0f), glm::vec4(1.0f), shaders::msmPowers(0.5f)}) {
      for (float zf : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        const float g = shaders::msmShadowIntensity(b, zf, bias);
        EXPECT_TRUE(std::isfinite(g));
        EXPECT_GE(g, 0.0f);
        EXPECT_LE(g, 1.0f);
      }
    }
  }
  // A single depth: in front of it lit, far behind it shadowed.
  EXPECT_NEAR(shaders::msmShadowIntensity(shaders::msmPowers(0.5f), 0.3f, 3e-6f), 0.0f, 1e-3f);
  EXPECT_NEAR(shaders::msmShadowIntensity(shaders::msmPowers(0.5f), 0.8f, 3e-6f), 1.0f, 1e-2f);
}

}  // namespace
}  // namespace penumbra
