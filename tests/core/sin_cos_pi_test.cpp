// sinCosPi: the polynomial sine and cosine of pi x that CSM's encode and lookup share.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/shared/sin_cos_pi.h"

namespace penumbra {
namespace {

// Against sin and cos of pi x in double, over four periods both sides of 0 (CSM's receiver depths
// go below 0 by the offset, its depths to 1, and the reduction must hold for any period). The
// bound: the Taylor remainders (5.7e-8 and 6.4e-9) plus float's rounding of pi (8.7e-8
// relative, up to 1.4e-7 at u = pi/2) and of the polynomial's steps; measured 1.88e-7 (sine)
// and 1.46e-7 (cosine). Dropping a Taylor term (u^11: 3.6e-6 at pi/2) or a wrong sign of (-1)^n
// (an error of 2) fails it.
TEST(SinCosPi, IsWithinFloatRoundingOfSineAndCosineOfPiX) {
  double worstSin = 0.0, worstCos = 0.0;
  for (int i = -400000; i <= 400000; ++i) {
    const float x = float(i) / 100000.0f;
    const glm::vec2 v = shaders::sinCosPi(x);
    worstSin = std::max(worstSin, std::abs(double(v[0]) - std::sin(M_PI * double(x))));
    worstCos = std::max(worstCos, std::abs(double(v[1]) - std::cos(M_PI * double(x))));
  }
  EXPECT_LT(worstSin, 2.5e-7);
  EXPECT_LT(worstCos, 2.5e-7);
}

}  // namespace
}  // namespace penumbra
