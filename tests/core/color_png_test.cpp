// Colour output: the sRGB transfer function (IEC 61966-2-1) and the colour PNG writer, which
// applies it exactly once to the linear light penumbra renders.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "penumbra/image_io.h"
#include "penumbra/srgb.h"

namespace penumbra {
namespace {

TEST(Srgb, EncodesTheStandardsReferencePoints) {
  EXPECT_EQ(srgbFromLinear(0.0f), 0.0f);
  EXPECT_EQ(srgbFromLinear(1.0f), 1.0f);
  // The linear segment: 12.92 L.
  EXPECT_FLOAT_EQ(srgbFromLinear(0.001f), 0.01292f);
  // The two pieces meet at the threshold, 0.0031308 -> 0.04045 (to the standard's 5 digits).
  EXPECT_NEAR(srgbFromLinear(0.0031308f), 0.04045f, 1e-5f);
  EXPECT_NEAR(srgbFromLinear(std::nextafter(0.0031308f, 1.0f)), 0.04045f, 1e-5f);
  // Mid grey: 18% linear reflectance is encoded as 0.4614 (118 of 255); 0.2140 as 0.4999.
  EXPECT_NEAR(srgbFromLinear(0.18f), 0.46135f, 1e-4f);
  EXPECT_NEAR(srgbFromLinear(0.2140f), 0.49993f, 1e-4f);
  // Out of range and NaN are clamped.
  EXPECT_EQ(srgbFromLinear(-0.5f), 0.0f);
  EXPECT_EQ(srgbFromLinear(2.0f), 1.0f);
  EXPECT_EQ(srgbFromLinear(std::nanf("")), 0.0f);
}

TEST(Srgb, IsIncreasingOverTheWholeRange) {
  float previous = srgbFromLinear(0.0f);
  for (int i = 1; i <= 100000; ++i) {
    const float encoded = srgbFromLinear(float(i) / 100000.0f);
    ASSERT_GT(encoded, previous) << i;
    previous = encoded;
  }
}

// A PNG's samples are the encoding of the linear values, once: 0.2140 linear is 128/255 (+-1 for
// the 8-bit rounding). Not encoding would store 55; encoding twice, 188.
TEST(ColorPng, StoresTheSrgbEncodingOfLinearLightOnce) {
  Image linear(4, 1, 3, 0.0f);
  const float values[4] = {0.2140f, 0.0f, 1.0f, 0.001f};
  for (int x = 0; x < 4; ++x) {
    for (int c = 0; c < 3; ++c) linear.at(x, 0, c) = values[x];
  }
  const std::filesystem::path file =
      std::filesystem::path(::testing::TempDir()) / "srgb_encoding.png";
  writeColorPng(linear, file);
  const Image stored = readEncodedColorPng(file);
  ASSERT_EQ(stored.width(), 4);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(stored.at(0, 0, c) * 255.0f, 128.0f, 1.0f) << c;
    EXPECT_EQ(stored.at(1, 0, c), 0.0f) << c;
    EXPECT_EQ(stored.at(2, 0, c), 1.0f) << c;
    EXPECT_EQ(std::lround(stored.at(3, 0, c) * 255.0f), 3) << c;  // 12.92 * 0.001 * 255 = 3.29
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace penumbra
