// Summed-area tables: box means equal long-double brute force within the stated bound (half a
// step, at most R * 2^-32, and the mean's double rounding), at the sizes where a float SAT falls
// apart (2048^2, 4096^2) and at the ends of fp32.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "penumbra/summed_area_table.h"

namespace penumbra {
namespace {

// Moment-like content: a half-lit, half-dark map with noise, the worst case for float prefix sums.
Image shadowLikeImage(int size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(0.0f, 0.1f);
  Image image(size, size, 2);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float z = (x < size / 2 ? 0.2f : 0.9f) + noise(rng);
      image.at(x, y, 0) = z;
      image.at(x, y, 1) = z * z;
    }
  }
  return image;
}

long double bruteMean(const Image& image, int x0, int y0, int x1, int y1, int c) {
  long double sum = 0.0L;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) sum += image.at(x, y, c);
  }
  return sum / ((long double)(x1 - x0 + 1) * (y1 - y0 + 1));
}

void expectBoxesWithinBound(int size) {
  const Image image = shadowLikeImage(size, unsigned(size));
  const SummedAreaTable sat(image);
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> coordinate(0, size - 1);
  double worst = 0.0;
  // Single texels, small boxes, and boxes spanning most of the map.
  for (int i = 0; i < 60; ++i) {
    int x0 = coordinate(rng), y0 = coordinate(rng);
    const int extent = i < 20 ? 0 : (i < 40 ? 7 : size / 2);
    const int x1 = std::min(size - 1, x0 + extent), y1 = std::min(size - 1, y0 + extent);
    for (int c = 0; c < 2; ++c) {
      const double error = double(std::abs((long double)sat.boxMean(x0, y0, x1, y1, c) -
                                           bruteMean(image, x0, y0, x1, y1, c)));
      ASSERT_LE(error, sat.errorBound(c)) << size << "^2 box " << x0 << "," << y0 << " " << extent;
      worst = std::max(worst, error);
    }
  }
  EXPECT_LT(sat.errorBound(0), 1e-9);
  ::testing::Test::RecordProperty("worst_error_" + std::to_string(size), std::to_string(worst));
}

TEST(SummedAreaTable, BoxMeansStayWithinTheBoundAt2048) {
  expectBoxesWithinBound(2048);
}

TEST(SummedAreaTable, BoxMeansStayWithinTheBoundAt4096) {
  expectBoxesWithinBound(4096);
}

TEST(SummedAreaTable, WholeImageAndClampedBoxes) {
  const Image image = shadowLikeImage(64, 9);
  const SummedAreaTable sat(image);
  EXPECT_LE(std::abs(sat.boxMean(0, 0, 63, 63, 0) - bruteMean(image, 0, 0, 63, 63, 0)),
            (long double)sat.errorBound(0));
  EXPECT_LE(std::abs(sat.boxMean(-5, -5, 100, 100, 1) - bruteMean(image, 0, 0, 63, 63, 1)),
            (long double)sat.errorBound(1));
  EXPECT_NEAR(sat.boxMean(10, 3, 10, 3, 0), image.at(10, 3, 0), sat.errorBound(0));
}

// The grid at the ends of fp32 (shared/summed_area.h): a narrow range far from zero (a value
// times the scale near 2^55), negative values, a constant channel of huge magnitude (its own
// magnitude's step) and a range under 2^-95 (the step held at 2^-127, the values off its grid).
// Each channel's step is the power of two the header derives: 2^(e-32) with 2^(e-1) <= R < 2^e.
// The box means against long double, within the bound (quantisation and the mean's rounding).
TEST(SummedAreaTable, ChannelsAtTheEndsOfFp32KeepTheBound) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> steps(0, 3);
  Image image(64, 64, 4);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      image.at(x, y, 0) = 1000.0f + std::ldexp(float(steps(rng)), -14);  // fp32's spacing there
      image.at(x, y, 1) = -3.5f - 0.25f * float(steps(rng));
      image.at(x, y, 2) = 1e30f;
      image.at(x, y, 3) = std::ldexp(1.0f + std::ldexp(float(steps(rng)), -20), -110);
    }
  }
  const SummedAreaTable sat(image);
  EXPECT_EQ(sat.step(0), std::ldexp(1.0, -45));   // R = 1.5 * 2^-14
  EXPECT_EQ(sat.step(1), std::ldexp(1.0, -33));   // R = 0.375
  EXPECT_EQ(sat.step(2), std::ldexp(1.0, 68));    // 1e30 in [2^99, 2^100)
  EXPECT_EQ(sat.step(3), std::ldexp(1.0, -127));  // R = 1.5 * 2^-130, below 2^-95
  // The centre on the grid at or below the midpoint (2^-110 (1 + 1.5 * 2^-20)), not on it.
  EXPECT_EQ(sat.centre(3), std::ldexp(1.0, -110));
  const int boxes[][4] = {{0, 0, 63, 63}, {5, 7, 5, 7}, {10, 20, 17, 50}, {0, 31, 63, 32}};
  for (const auto& b : boxes) {
    for (int c = 0; c < 4; ++c) {
      const long double exact = bruteMean(image, b[0], b[1], b[2], b[3], c);
      const long double mean = sat.boxMean(b[0], b[1], b[2], b[3], c);
      EXPECT_LE(std::abs(mean - exact), (long double)sat.errorBound(c))
          << "channel " << c << " box " << b[0] << "," << b[1] << " " << b[2] << "," << b[3];
    }
    EXPECT_EQ(sat.boxMean(b[0], b[1], b[2], b[3], 2), 1e30f);
  }
}

TEST(SummedAreaTable, ConstantImagesAreExact) {
  const Image image(32, 32, 1, 0.375f);
  const SummedAreaTable sat(image);
  EXPECT_EQ(sat.boxMean(3, 4, 20, 30, 0), 0.375);
}

}  // namespace
}  // namespace penumbra
