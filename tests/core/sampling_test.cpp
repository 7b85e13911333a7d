// GL-convention bilinear and trilinear sampling.
#include <gtest/gtest.h>

#include "penumbra/filters.h"
#include "penumbra/sampling.h"

namespace penumbra {
namespace {

Image ramp() {
  Image image(4, 2, 1);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) image.at(x, y) = float(x + 4 * y);
  }
  return image;
}

TEST(Sampling, TexelCentresReturnTexels) {
  const Image image = ramp();
  float v = 0.0f;
  sampleBilinear(image, (2 + 0.5f) / 4.0f, (1 + 0.5f) / 2.0f, {&v, 1});
  EXPECT_FLOAT_EQ(v, 6.0f);
}

TEST(Sampling, BilinearInterpolatesBetweenCentresAndClampsAtEdges) {
  const Image image = ramp();
  float v = 0.0f;
  sampleBilinear(image, 2.0f / 4.0f, 0.5f / 2.0f, {&v, 1});  // halfway between texels 1 and 2
  EXPECT_FLOAT_EQ(v, 1.5f);
  sampleBilinear(image, 0.5f, 0.5f, {&v, 1});  // centre of the 2x2 block at (1..2, 0..1)
  EXPECT_FLOAT_EQ(v, (1 + 2 + 5 + 6) / 4.0f);
  sampleBilinear(image, 0.0f, 0.0f, {&v, 1});  // corner: clamp to edge
  EXPECT_FLOAT_EQ(v, 0.0f);
}

TEST(Sampling, TrilinearBlendsLevels) {
  const auto mips = buildMipChain(ramp());
  float a = 0.0f, b = 0.0f, t = 0.0f;
  sampleBilinear(mips[0], 0.3f, 0.6f, {&a, 1});
  sampleBilinear(mips[1], 0.3f, 0.6f, {&b, 1});
  sampleTrilinear(mips, 0.3f, 0.6f, 0.0f, {&t, 1});
  EXPECT_FLOAT_EQ(t, a);
  sampleTrilinear(mips, 0.3f, 0.6f, 0.25f, {&t, 1});
  EXPECT_FLOAT_EQ(t, 0.75f * a + 0.25f * b);
  sampleTrilinear(mips, 0.3f, 0.6f, 99.0f, {&t, 1});  // clamps to the 1x1 level
  EXPECT_FLOAT_EQ(t, mips.back().at(0, 0));
}

}  // namespace
}  // namespace penumbra
