// tune's objectives (src/tune/path_error.h) on images whose errors are set by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "path_error.h"

namespace penumbra::tune {
namespace {

// A 3 x 1 frame: the target 0.5 everywhere, measured on the first two pixels only.
FrameTarget target() {
  FrameTarget t{Image(3, 1, 1, 0.5f), Image(3, 1, 1, 1.0f)};
  t.mask.at(2, 0) = 0.0f;
  return t;
}

Image frame(float a, float b, float unmeasured) {
  Image v(3, 1, 1);
  v.at(0, 0) = a;
  v.at(1, 0) = b;
  v.at(2, 0) = unmeasured;
  return v;
}

TEST(TuneObjective, PoolsTheSquaredErrorsOfTheMeasuredPixels) {
  const PathTargets targets{3, 1, {target(), target()}};
  // Frame 0: errors +0.2 and -0.1; frame 1: 0 and +0.3; the unmeasured pixel is far off.
  const std::vector<Image> v{frame(0.7f, 0.4f, 0.0f), frame(0.5f, 0.8f, 1.0f)};
  const SetError both = errorOver(ErrorMeasure::Rmse, 4.0, v, targets, 0, 2);
  // float images: 0.7f - 0.5f etc. are exact to 1e-7 of the decimal errors.
  EXPECT_NEAR(both.rmse, std::sqrt((0.04 + 0.01 + 0.0 + 0.09) / 4.0), 1e-6);
  EXPECT_EQ(both.measure, both.rmse);
  const SetError second = errorOver(ErrorMeasure::Rmse, 4.0, v, targets, 1, 2);
  EXPECT_NEAR(second.rmse, std::sqrt(0.09 / 2.0), 1e-6);
}

TEST(TuneObjective, WeighsALeakNotAnOverDarkening) {
  const PathTargets targets{3, 1, {target()}};
  // +0.2 is a leak (lighter than the target), -0.1 an over-darkening.
  const std::vector<Image> v{frame(0.7f, 0.4f, 0.5f)};
  const SetError e = errorOver(ErrorMeasure::LeakWeighted, 4.0, v, targets, 0, 1);
  EXPECT_NEAR(e.measure, std::sqrt((4.0 * 0.04 + 0.01) / 2.0), 1e-6);
  EXPECT_NEAR(e.rmse, std::sqrt((0.04 + 0.01) / 2.0), 1e-6);
}

TEST(TuneObjective, FlickerAddsTheChangeBeyondTheTargets) {
  const PathTargets targets{3, 1, {target(), target()}};
  // The targets hold still; the setting's visibility moves by 0.2 on one pixel of two.
  const std::vector<Image> v{frame(0.5f, 0.5f, 0.0f), frame(0.7f, 0.5f, 0.0f)};
  const SetError e = errorOver(ErrorMeasure::Flicker, 4.0, v, targets, 0, 2);
  EXPECT_NEAR(e.rmse, std::sqrt(0.04 / 4.0), 1e-6);
  EXPECT_NEAR(e.measure, e.rmse + 0.2 / 2.0, 1e-6);
}

}  // namespace
}  // namespace penumbra::tune
