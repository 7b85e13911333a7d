// Step-shape measures on curves whose answers are known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/error.h"
#include "penumbra/step_shape.h"

namespace penumbra {
namespace {

// A linear ramp from 1 at x = a to 0 at x = b, sampled every 1/1000 over [-0.5, 0.5]; with
// a ringing bump of height `bumpHeight` at x = 0.3 (shadowed side) and a trough of depth
// `troughDepth` at `trough` (lit side).
StepCurve ramp(float a, float b, float bumpHeight = 0.0f, float troughDepth = 0.0f,
               float trough = -0.3f) {
  const float bump = 0.3f;
  StepCurve c;
  for (int i = 0; i <= 1000; ++i) {
    const float x = -0.5f + float(i) / 1000.0f;
    float v = x <= a ? 1.0f : (x >= b ? 0.0f : (b - x) / (b - a));
    // Triangular bumps 0.02 wide: a local maximum at `bump`, a local minimum at `trough`.
    v += bumpHeight * std::max(0.0f, 1.0f - std::abs(x - bump) / 0.01f);
    v -= troughDepth * std::max(0.0f, 1.0f - std::abs(x - trough) / 0.01f);
    c.x.push_back(x);
    c.v.push_back(v);
  }
  return c;
}

// Samples are 1e-3 apart: the crossings land within a sample of the exact ones.
constexpr float kSample = 1.001e-3f;

TEST(StepShape, MeasuresTheFallOfALinearRamp) {
  const StepShape s = measureStepShape(ramp(-0.1f, 0.1f));
  EXPECT_NEAR(s.halfCrossing, 0.0f, kSample);
  EXPECT_NEAR(s.lit90, -0.08f, kSample);  // 0.9 at a + 0.1 (b - a)
  EXPECT_NEAR(s.shadow10, 0.08f, kSample);
  EXPECT_NEAR(s.transitionWidth, 0.16f, 2.0f * kSample);
  EXPECT_FLOAT_EQ(s.ringing, 0.0f);
  EXPECT_FLOAT_EQ(s.firstTroughDistance, 0.0f);
}

TEST(StepShape, RingingIsHowFarTheCurveTurnsBack) {
  // The ripples are linear between samples that hit their peaks: exact but for float rounding.
  const StepShape litSide = measureStepShape(ramp(-0.1f, 0.1f, 0.04f, 0.07f, -0.25f));
  EXPECT_NEAR(litSide.ringing, 0.07f, 1e-5f);
  EXPECT_NEAR(litSide.firstTroughDistance, 0.25f, kSample);
  const StepShape shadowSide = measureStepShape(ramp(-0.1f, 0.1f, 0.07f, 0.02f));
  EXPECT_NEAR(shadowSide.ringing, 0.07f, 1e-5f);
}

TEST(StepShape, ErrorAreaOfARampIsItsTwoTriangles) {
  // For a ramp over [-a, a], |v - H| rises from 0 to 1/2 on each side of 0: two triangles of
  // area a/4. Linear between samples, so the trapezoids are exact but for float rounding.
  const StepCurve c = ramp(-0.1f, 0.1f);
  EXPECT_NEAR(stepErrorArea(c, -0.5f, 0.5f), 0.05, 1e-5);
  EXPECT_NEAR(stepErrorArea(c, 0.0f, 0.5f), 0.025, 1e-5);
  EXPECT_NEAR(stepErrorMax(c, 0.05f, 0.5f), 0.25f, kSample);
  EXPECT_DOUBLE_EQ(stepErrorArea(ramp(-0.1f, 0.1f), 0.2f, 0.5f), 0.0);
}

TEST(StepShape, ErrorAreaSplitsAnIntervalAtTheStep) {
  // Always lit, with no sample at x = 0: the error is 0 before the step and 1 after it.
  const StepCurve alwaysLit{{-0.5f, 0.5f, 0.75f}, {1.0f, 1.0f, 1.0f}};
  EXPECT_DOUBLE_EQ(stepErrorArea(alwaysLit, -0.5f, 0.75f), 0.75);
  // A sample exactly at x = 0: the interval after it is on the shadowed side (step 0) from its
  // first point on, so lit at 0 falling to 0 at 0.5 is a triangle of area 1/4.
  const StepCurve litAtTheStep{{-0.5f, 0.0f, 0.5f}, {1.0f, 1.0f, 0.0f}};
  EXPECT_DOUBLE_EQ(stepErrorArea(litAtTheStep, -0.5f, 0.5f), 0.25);
}

TEST(StepShape, RejectsCurvesItCannotMeasure) {
  StepCurve flat{{0.0f, 0.1f, 0.2f}, {1.0f, 1.0f, 1.0f}};
  EXPECT_THROW(measureStepShape(flat), Error);
  StepCurve unordered{{0.0f, 0.2f, 0.1f}, {1.0f, 0.0f, 0.0f}};
  EXPECT_THROW(measureStepShape(unordered), Error);
  // Falls through 1/2 but never from 0.9, or never down to 0.1: no transition width to give.
  StepCurve shallow{{0.0f, 0.1f, 0.2f}, {0.8f, 0.4f, 0.0f}};
  EXPECT_THROW(measureStepShape(shallow), Error);
  StepCurve stuck{{0.0f, 0.1f, 0.2f}, {1.0f, 0.4f, 0.3f}};
  EXPECT_THROW(measureStepShape(stuck), Error);
  StepCurve shortCurve{{0.0f, 0.1f}, {1.0f, 0.0f}};
  EXPECT_THROW(stepErrorArea(shortCurve, 0.0f, 1.0f), Error);
}

}  // namespace
}  // namespace penumbra
