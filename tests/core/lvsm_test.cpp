// Layered VSM (thesis §4.1): eq. 4.2 warps, exact zero past a well-placed split, transitions.
#include <gtest/gtest.h>

#include "penumbra/depth_distribution.h"
#include "penumbra/params.h"
#include "region_helpers.h"
#include "penumbra/shared/lvsm.h"

namespace penumbra {
namespace {

using testing::float32Params;

TEST(Lvsm, WarpFollowsThesisEquation4_2) {
  const glm::vec2 range(0.4f, 0.6f);
  EXPECT_EQ(shaders::lvsmWarp(0.3f, range), 0.0f);
  EXPECT_EQ(shaders::lvsmWarp(0.4f, range), 0.0f);
  EXPECT_NEAR(shaders::lvsmWarp(0.45f, range), 0.25f, 1e-6f);
  EXPECT_EQ(shaders::lvsmWarp(0.6f, range), 1.0f);
  EXPECT_EQ(shaders::lvsmWarp(0.9f, range), 1.0f);
}

TEST(Lvsm, LayersOverlapByDelta) {
  TechniqueParams params = float32Params();
  setParam(Technique::Lvsm, params, "splits", "0.25,0.5,0.75");
  params.lvsm.overlap = 0.02f;
  const glm::vec2 first = shaders::lvsmLayerRange(0, params.lvsm);
  const glm::vec2 second = shaders::lvsmLayerRange(1, params.lvsm);
  const glm::vec2 last = shaders::lvsmLayerRange(3, params.lvsm);
  EXPECT_FLOAT_EQ(first.x, 0.0f);
  EXPECT_FLOAT_EQ(first.y, 0.27f);
  EXPECT_FLOAT_EQ(second.x, 0.23f);
  EXPECT_FLOAT_EQ(second.y, 0.52f);
  EXPECT_FLOAT_EQ(last.x, 0.73f);
  EXPECT_FLOAT_EQ(last.y, 1.0f);
}

// minVariance is a floor on the variance of the layer's warped depth, as its documentation says
// (unlike VSM's and EVSM's, in linear depth^2): a flat occluder (variance 0) gives
// f / (f + (t_r - t_o)^2) in warped depth t, stretched by 1 / (layer width).
TEST(Lvsm, MinVarianceFloorsTheLayersWarpedDepthAsDocumented) {
  TechniqueParams params = float32Params();
  setParam(Technique::Lvsm, params, "splits", "0.25,0.5,0.75");
  params.lvsm.overlap = 0.01f;  // layer 1 spans [0.24, 0.51]: width 0.27
  params.lvsm.minVariance = 1e-4f;
  const glm::vec2 range = shaders::lvsmLayerRange(1, params.lvsm);
  const float occluder = 0.3f, receiver = 0.31f;
  const float t = shaders::lvsmWarp(occluder, range);
  const float dt = shaders::lvsmWarp(receiver, range) - t;  // 0.01 / 0.27
  const float v = shaders::lvsmLayerVisibility(glm::vec2(t, t * t), receiver, 1, params.lvsm);
  EXPECT_NEAR(v, 1e-4f / (1e-4f + dt * dt), 1e-4f);  // fp32 of t^2 - t^2 against the floor
  // In linear depth^2 the same floor would give 1e-4 / (1e-4 + 0.01^2) = 0.5.
  EXPECT_LT(v, 0.2f);
  bool documented = false;
  for (const ParamSpec& spec : techniqueParamSpecs(Technique::Lvsm)) {
    if (spec.name == "minVariance") {
      documented = spec.description.find("warped depth^2") != std::string_view::npos;
    }
  }
  EXPECT_TRUE(documented) << "LVSM's minVariance must say it is in warped depth^2";
  for (Technique linear : {Technique::Vsm, Technique::Evsm4}) {
    for (const ParamSpec& spec : techniqueParamSpecs(linear)) {
      if (spec.name == "minVariance") {
        EXPECT_NE(spec.description.find("linear depth^2"), std::string_view::npos)
            << techniqueId(linear);
      }
    }
  }
}

TEST(Lvsm, SplitBetweenSecondAndThirdObjectGivesZeroVisibilityForTheThird) {
  TechniqueParams params = float32Params();
  params.lvsm.minVariance = 0.0f;
  setParam(Technique::Lvsm, params, "splits", "0.6");
  const std::vector<DepthSample> region{{0.2f, 0.5f}, {0.4f, 0.5f}};
  const float receiverC = 0.8f;
  EXPECT_EQ(evaluateOnRegion(Technique::Lvsm, params, region, receiverC), 0.0f);
  EXPECT_GT(evaluateOnRegion(Technique::Vsm, params, region, receiverC), 0.02f);
  // With the default variance floor the result stays negligible.
  params.lvsm.minVariance = shaders::lvsmDefaultParams().minVariance;
  EXPECT_LT(evaluateOnRegion(Technique::Lvsm, params, region, receiverC), 1e-3f);
}

TEST(Lvsm, WithinOneLayerItIsVsmOfTheWarpedDepths) {
  TechniqueParams params = float32Params();
  setParam(Technique::Lvsm, params, "layers", "1");
  const std::vector<DepthSample> region{{0.3f, 0.4f}, {0.7f, 0.6f}};
  for (float receiver : {0.35f, 0.5f, 0.9f}) {
    EXPECT_NEAR(evaluateOnRegion(Technique::Lvsm, params, region, receiver),
                evaluateOnRegion(Technique::Vsm, params, region, receiver), 1e-6f);
  }
}

TEST(Lvsm, TransitionBlendMakesVisibilityContinuousAtSplits) {
  TechniqueParams params = float32Params();
  setParam(Technique::Lvsm, params, "splits", "0.5");
  params.lvsm.overlap = 0.05f;
  const std::vector<DepthSample> region{{0.3f, 0.3f}, {0.45f, 0.3f}, {0.7f, 0.4f}};
  const float below = 0.5f - 1e-4f, above = 0.5f + 1e-4f;
  params.lvsm.transition = 0.0f;
  const float jump = std::abs(evaluateOnRegion(Technique::Lvsm, params, region, below) -
                              evaluateOnRegion(Technique::Lvsm, params, region, above));
  params.lvsm.transition = 0.05f;
  const float blended = std::abs(evaluateOnRegion(Technique::Lvsm, params, region, below) -
                                 evaluateOnRegion(Technique::Lvsm, params, region, above));
  EXPECT_GT(jump, 0.01f);
  EXPECT_LT(blended, 0.1f * jump);
}

}  // namespace
}  // namespace penumbra
