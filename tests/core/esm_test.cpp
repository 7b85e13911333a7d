// ESM (ESM paper §3; Salvi): convergence to PCF as c grows, threshold classification, and
// log-space filtering that agrees with linear space and stays finite for huge c.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "penumbra/depth_distribution.h"
#include "penumbra/error.h"
#include "penumbra/params.h"
#include "region_helpers.h"
#include "penumbra/shared/esm.h"

namespace penumbra {
namespace {

using testing::float32Params;

// Occluders all in front of the receiver plane, which fills the rest of the region.
const std::vector<DepthSample> kFrontOccluders{{0.3f, 0.25f}, {0.45f, 0.35f}};

float esmError(TechniqueParams params, float c, int filterSpace) {
  params.esm.exponent = c;
  params.esm.filterSpace = filterSpace;
  float worst = 0.0f;
  for (float receiver : {0.5f, 0.6f, 0.8f}) {
    const auto region = regionWithReceiver(kFrontOccluders, receiver);
    const float pcf = exactVisibility(region, receiver);
    worst =
        std::max(worst, std::abs(evaluateOnRegion(Technique::Esm, params, region, receiver) - pcf));
  }
  return worst;
}

TEST(Esm, ApproachesPcfAsTheExponentGrowsWhenEveryOccluderIsInFront) {
  const TechniqueParams params = float32Params();
  const float e10 = esmError(params, 10.0f, shaders::kEsmFilterLinear);
  const float e40 = esmError(params, 40.0f, shaders::kEsmFilterLinear);
  const float e80 = esmError(params, 80.0f, shaders::kEsmFilterLinear);
  EXPECT_GT(e10, e40);
  EXPECT_GT(e40, e80);
  EXPECT_LT(e80, 0.02f);
  // Log space goes further than fp32's exp range allows.
  EXPECT_LT(esmError(params, 1000.0f, shaders::kEsmFilterLog), 1e-5f);
}

TEST(Esm, ThresholdClassificationFlagsOccludersBehindTheReceiver) {
  TechniqueParams params = float32Params();
  const float receiver = 0.5f;
  // Valid: every occluder in front of the receiver.
  const auto valid = regionWithReceiver(kFrontOccluders, receiver);
  const float validStore = filterRegion(Technique::Esm, params, valid)[0];
  EXPECT_FALSE(shaders::esmFailsThreshold(validStore, receiver, params.esm));
  // Violated: part of the region lies behind the receiver (a non-planar receiver).
  const std::vector<DepthSample> violated{{0.3f, 0.5f}, {0.6f, 0.5f}};
  const float violatedStore = filterRegion(Technique::Esm, params, violated)[0];
  EXPECT_TRUE(shaders::esmFailsThreshold(violatedStore, receiver, params.esm));
  EXPECT_EQ(shaders::esmVisibility(violatedStore, receiver, params.esm), 1.0f);
  // Both filtering spaces classify alike.
  params.esm.filterSpace = shaders::kEsmFilterLog;
  EXPECT_FALSE(shaders::esmFailsThreshold(filterRegion(Technique::Esm, params, valid)[0], receiver,
                                          params.esm));
  EXPECT_TRUE(shaders::esmFailsThreshold(filterRegion(Technique::Esm, params, violated)[0],
                                         receiver, params.esm));
}

TEST(Esm, LogSpaceAndLinearSpaceFilteringAgreeWhereBothAreFinite) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  TechniqueParams linear = float32Params();
  TechniqueParams logSpace = linear;
  logSpace.esm.filterSpace = shaders::kEsmFilterLog;
  for (int i = 0; i < 300; ++i) {
    const float c = 1.0f + 79.0f * unit(rng);
    linear.esm.exponent = logSpace.esm.exponent = c;
    std::vector<DepthSample> region{{unit(rng), 0.2f}, {unit(rng), 0.3f}, {unit(rng), 0.5f}};
    const float receiver = unit(rng);
    const float a = evaluateOnRegion(Technique::Esm, linear, region, receiver);
    const float b = evaluateOnRegion(Technique::Esm, logSpace, region, receiver);
    EXPECT_NEAR(a, b, 1e-5f + 1e-4f * a) << "c " << c << " receiver " << receiver;
  }
}

TEST(Esm, LogSpaceHelpersStayFiniteFarBeyondFp32ExpRange) {
  const float c = 5000.0f;  // exp(5000 z) overflows fp32 for any z > 0.0178
  // Both orders: the second term below the peak, and above it (the peak moves).
  for (const auto& [first, second] : {std::pair{0.2f, 0.9f}, std::pair{0.9f, 0.2f}}) {
    const glm::vec2 sum = shaders::esmLogSumAdd(shaders::esmLogSumStart(first, 0.5f), second, 0.5f, c);
    const float value = shaders::esmLogSumValue(sum, c);
    ASSERT_TRUE(std::isfinite(value));
    EXPECT_NEAR(value, 0.9f + std::log(0.5f) / c, 1e-6f);  // the far term dominates completely
  }
  // Equal terms add to twice the weight: ln 2 / c above.
  const glm::vec2 equal = shaders::esmLogSumAdd(shaders::esmLogSumStart(0.5f, 1.0f), 0.5f, 1.0f, c);
  EXPECT_NEAR(shaders::esmLogSumValue(equal, c), 0.5f + std::log(2.0f) / c, 1e-7f);
  // Terms within fp32 exp range combine exactly: ln(0.25 e^{c 0.3} + 0.75 e^{c 0.31}) / c.
  const float small = 40.0f;
  const glm::vec2 mixed =
      shaders::esmLogSumAdd(shaders::esmLogSumStart(0.3f, 0.25f), 0.31f, 0.75f, small);
  EXPECT_NEAR(shaders::esmLogSumValue(mixed, small),
              std::log(0.25 * std::exp(40.0 * 0.3) + 0.75 * std::exp(40.0 * 0.31)) / 40.0, 1e-6);
  TechniqueParams params = float32Params();
  params.esm.filterSpace = shaders::kEsmFilterLog;
  params.esm.exponent = c;
  const std::vector<DepthSample> region{{0.2f, 0.5f}, {1.0f, 0.5f}};
  const float v = evaluateOnRegion(Technique::Esm, params, region, 1.0f);
  EXPECT_TRUE(std::isfinite(v));
  EXPECT_NEAR(v, 0.5f, 1e-4f);
}

TEST(Esm, LinearSpaceRejectsExponentsFp32CannotHold) {
  TechniqueParams params = float32Params();
  setParam(Technique::Esm, params, "c", "120");
  EXPECT_THROW(validateParams(Technique::Esm, params), Error);
  setParam(Technique::Esm, params, "filtering", "log");
  EXPECT_NO_THROW(validateParams(Technique::Esm, params));
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST(EsmFallback, ZmaxFlagsOccludersBehindTheReceiverBeyondTheOffset) {
  shaders::EsmParams p = shaders::esmDefaultParams();
  p.zmaxOffset = 0.01f;
  EXPECT_FALSE(shaders::esmFailsZmax(0.505f, 0.5f, p));
  EXPECT_TRUE(shaders::esmFailsZmax(0.52f, 0.5f, p));
}

}  // namespace
}  // namespace penumbra
