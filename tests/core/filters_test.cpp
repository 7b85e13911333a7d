// Reference filters against brute force: separable equals 2D, blur preserves the mean, min/max
// filters, mip levels equal block averages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "penumbra/error.h"
#include "penumbra/filters.h"

namespace penumbra {
namespace {

Image randomImage(int w, int h, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Image image(w, h, channels);
  for (float& v : image.data()) v = unit(rng);
  return image;
}

// Brute-force 2D convolution with the product of the 1D weights and edge clamping.
Image bruteForce2D(const Image& in, const std::vector<float>& weights) {
  const int r = int(weights.size() / 2);
  Image out(in.width(), in.height(), in.channels());
  for (int y = 0; y < in.height(); ++y) {
    for (int x = 0; x < in.width(); ++x) {
      for (int c = 0; c < in.channels(); ++c) {
        double sum = 0.0;
        for (int j = -r; j <= r; ++j) {
          for (int i = -r; i <= r; ++i) {
            sum += double(weights[size_t(i + r)]) * weights[size_t(j + r)] *
                   in.clamped(x + i, y + j, c);
          }
        }
        out.at(x, y, c) = float(sum);
      }
    }
  }
  return out;
}

TEST(Filters, WeightsSumToOne) {
  for (int radius : {0, 1, 3, 15, 31}) {
    for (BlurKernel kernel : {BlurKernel::Box, BlurKernel::Gaussian}) {
      const auto w = blurWeights({kernel, radius, std::max(1.0f, radius / 2.0f)});
      double sum = 0.0;
      for (float v : w) sum += v;
      EXPECT_NEAR(sum, 1.0, 1e-6);
      EXPECT_EQ(int(w.size()), 2 * radius + 1);
    }
  }
}

TEST(Filters, SeparableEqualsBruteForce2D) {
  const Image image = randomImage(37, 23, 2, 1);
  for (BlurSpec spec : {BlurSpec{BlurKernel::Box, 2, 1.0f}, BlurSpec{BlurKernel::Gaussian, 3, 1.5f},
                        BlurSpec{BlurKernel::Gaussian, 7, 3.0f}}) {
    const Image separable = separableFilter(image, spec);
    const Image reference = bruteForce2D(image, blurWeights(spec));
    for (size_t i = 0; i < separable.data().size(); ++i) {
      ASSERT_NEAR(separable.data()[i], reference.data()[i], 2e-6f);
    }
  }
}

TEST(Filters, BlurPreservesTheMean) {
  // A random interior inside a constant border wider than the kernel: clamping adds nothing.
  const int border = 8;
  Image image(64, 48, 1, 0.25f);
  const Image noise = randomImage(64, 48, 1, 2);
  for (int y = border; y < 48 - border; ++y) {
    for (int x = border; x < 64 - border; ++x) image.at(x, y) = noise.at(x, y);
  }
  auto mean = [](const Image& im) {
    double s = 0.0;
    for (float v : im.data()) s += v;
    return s / double(im.data().size());
  };
  EXPECT_NEAR(mean(gaussianBlur(image, 5, 2.0f)), mean(image), 1e-6);
  EXPECT_NEAR(mean(boxBlur(image, 7)), mean(image), 1e-6);
}

TEST(Filters, MinAndMaxFiltersTakeTheExtremeOverTheSquare) {
  const Image image = randomImage(20, 17, 1, 3);
  const int r = 2;
  const Image lo = minFilter(image, r), hi = maxFilter(image, r);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      float expectedLo = 1.0f, expectedHi = 0.0f;
      for (int j = -r; j <= r; ++j) {
        for (int i = -r; i <= r; ++i) {
          expectedLo = std::min(expectedLo, image.clamped(x + i, y + j));
          expectedHi = std::max(expectedHi, image.clamped(x + i, y + j));
        }
      }
      ASSERT_EQ(lo.at(x, y), expectedLo);
      ASSERT_EQ(hi.at(x, y), expectedHi);
    }
  }
}

TEST(Filters, PerChannelReductionsMixMinMaxAndMean) {
  const Image image = randomImage(16, 16, 3, 4);
  const std::vector<ChannelReduction> r{ChannelReduction::Min, ChannelReduction::Max,
                                        ChannelReduction::Mean};
  const Image mixed = separableFilter(image, {BlurKernel::Box, 1, 1.0f}, r);
  const Image lo = minFilter(image, 1), hi = maxFilter(image, 1), mean = boxBlur(image, 1);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(mixed.at(x, y, 0), lo.at(x, y, 0));
      EXPECT_EQ(mixed.at(x, y, 1), hi.at(x, y, 1));
      EXPECT_FLOAT_EQ(mixed.at(x, y, 2), mean.at(x, y, 2));
    }
  }
}

// ESM's log-space channel (Salvi) under both kernels, against ln(sum of w exp(c v)) / c in double
// over the clamped taps, one axis at a time: the box sums its taps at unit weight and scales the
// log-space sum once (shared/channel_reduction.h scaleTapWeights), the Gaussian weighs each tap.
// Values spread over 0.1 at c = 80 put the sum's terms across 8 orders of magnitude.
TEST(Filters, LogMeanExpEqualsTheLogOfTheWeightedMeanOfExponentials) {
  const Image image = randomImage(24, 1, 1, 9);
  const float c = 80.0f;
  const std::vector<ChannelReduction> logSpace{ChannelReduction::LogMeanExp};
  for (const BlurSpec spec :
       {BlurSpec{BlurKernel::Box, 3, 1.0f}, BlurSpec{BlurKernel::Gaussian, 3, 1.5f}}) {
    const std::vector<float> w = blurWeights(spec);
    Image spread = image;
    for (float& v : spread.data()) v = 0.5f + 0.1f * v;
    const Image filtered = separableFilterPass(spread, spec, true, logSpace, c);
    for (int x = 0; x < spread.width(); ++x) {
      double sum = 0.0;
      for (int i = -spec.radius; i <= spec.radius; ++i) {
        const int tap = std::clamp(x + i, 0, spread.width() - 1);
        sum += double(w[size_t(i + spec.radius)]) * std::exp(double(c) * spread.at(tap, 0));
      }
      // fp32 throughout: exp of a difference of at most 8 and the log of a sum of 7 terms in
      // [w, 1], each within a few ulps, then divided by c = 80: under 1e-6 of values near 0.5.
      EXPECT_NEAR(filtered.at(x, 0), std::log(sum) / c, 1e-6)
          << (spec.kernel == BlurKernel::Box ? "box" : "gaussian") << " texel " << x;
    }
  }
}

TEST(Filters, MipLevelsEqualBruteForceBlockReductions) {
  const Image image = randomImage(32, 16, 1, 5);
  const auto chain = buildMipChain(image);
  ASSERT_EQ(chain.size(), 6u);  // 32x16 ... 1x1
  const std::vector<ChannelReduction> maxOnly{ChannelReduction::Max};
  const auto maxChain = buildMipChain(image, maxOnly);
  for (size_t level = 0; level < chain.size(); ++level) {
    const int block = 1 << level;
    EXPECT_EQ(chain[level].width(), std::max(1, 32 / block));
    for (int y = 0; y < chain[level].height(); ++y) {
      for (int x = 0; x < chain[level].width(); ++x) {
        double sum = 0.0;
        float peak = 0.0f;
        int count = 0;
        for (int j = y * block; j < std::min(16, (y + 1) * block); ++j) {
          for (int i = x * block; i < (x + 1) * block; ++i) {
            sum += image.at(i, j);
            peak = std::max(peak, image.at(i, j));
            ++count;
          }
        }
        EXPECT_NEAR(chain[level].at(x, y), sum / count, 2e-6) << "level " << level;
        EXPECT_EQ(maxChain[level].at(x, y), peak);
      }
    }
  }
}

TEST(Filters, OddSizesFoldTheLeftoverTexelsIn) {
  Image image(3, 1, 1);
  image.at(0, 0) = 1.0f;
  image.at(1, 0) = 2.0f;
  image.at(2, 0) = 6.0f;
  const Image down = reduceMipLevel(image);
  ASSERT_EQ(down.width(), 1);
  EXPECT_FLOAT_EQ(down.at(0, 0), 3.0f);
}

TEST(Filters, BadArgumentsAreRejected) {
  const Image image(4, 4, 1);
  EXPECT_THROW(gaussianBlur(image, -1, 1.0f), Error);
  EXPECT_THROW(gaussianBlur(image, 2, 0.0f), Error);
  const std::vector<ChannelReduction> twoChannels{ChannelReduction::Min, ChannelReduction::Max};
  EXPECT_THROW(reduceMipLevel(image, twoChannels), Error);
  EXPECT_THROW(Image(0, 4, 1), Error);
}

}  // namespace
}  // namespace penumbra
