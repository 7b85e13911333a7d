// Separable blur, min/max filters and mip reduction over float images.
#include "penumbra/filters.h"

#include <algorithm>
#include <cassert>
#include <string>

#include "parallel.h"
#include "penumbra/error.h"
#include "penumbra/shared/channel_reduction.h"
#include "penumbra/shared/esm.h"
#include "penumbra/shared/filter_weights.h"
#include "penumbra/shared/mip_span.h"

namespace penumbra {
namespace {

ChannelReduction reductionOf(std::span<const ChannelReduction> reductions, int channel) {
  return reductions.empty() ? ChannelReduction::Mean : reductions[size_t(channel)];
}

void checkReductions(const Image& image, std::span<const ChannelReduction> reductions) {
  if (!reductions.empty() && int(reductions.size()) != image.channels()) {
    throw Error("filter given " + std::to_string(reductions.size()) +
                " channel reductions for an image of " + std::to_string(image.channels()) +
                " channels");
  }
}

shaders::ChannelAccumulator startReduction(ChannelReduction reduction, float logExponent) {
  return shaders::startReduction(int(reduction), logExponent);
}

// One 1D pass of `spec` along x (horizontal) or y with edge clamping. Taps that weigh alike are
// summed at unit weight and scaled once where `alike` says so, as the GPU's blur does
// (shared/channel_reduction.h scaleTapWeights).
Image filterPass(const Image& in, const BlurSpec& spec, bool horizontal,
                 std::span<const ChannelReduction> reductions, float logExponent,
                 AlikeTaps alikeTaps) {
  const std::vector<float> weights = blurWeights(spec);
  const bool alike = sumsTapsAtUnitWeight(spec, alikeTaps);
  Image out(in.width(), in.height(), in.channels());
  const int radius = spec.radius;
  detail::parallelForRows(in.height(), [&](int y) {
    for (int x = 0; x < in.width(); ++x) {
      for (int c = 0; c < in.channels(); ++c) {
        auto acc = startReduction(reductionOf(reductions, c), logExponent);
        for (int i = -radius; i <= radius; ++i) {
          float v = horizontal ? in.clamped(x + i, y, c) : in.clamped(x, y + i, c);
          acc = shaders::accumulateTap(acc, v, alike ? 1.0f : weights[size_t(i + radius)]);
        }
        if (alike) acc = shaders::scaleTapWeights(acc, weights[0]);
        out.at(x, y, c) = shaders::reductionResult(acc);
      }
    }
  });
  return out;
}

}  // namespace

AlikeTaps alikeTapsFor(Technique technique, const TechniqueParams& params) {
  const bool exponentials =
      technique == Technique::Evsm2 || technique == Technique::Evsm4 ||
      (technique == Technique::Esm && params.esm.filterSpace == shaders::kEsmFilterLinear);
  return exponentials ? AlikeTaps::Weighted : AlikeTaps::SummedThenScaled;
}

bool sumsTapsAtUnitWeight(const BlurSpec& spec, AlikeTaps alike) {
  return shaders::kernelTapsAlike(blurKernelId(spec.kernel)) &&
         alike == AlikeTaps::SummedThenScaled;
}

int blurKernelId(BlurKernel kernel) {
  return kernel == BlurKernel::Box ? shaders::kKernelBox : shaders::kKernelGaussian;
}

std::vector<float> blurWeights(const BlurSpec& spec) {
  if (spec.radius < 0 || spec.radius > shaders::kMaxBlurRadius) {
    throw Error("blur radius " + std::to_string(spec.radius) + " is out of range [0, " +
                std::to_string(shaders::kMaxBlurRadius) + "]");
  }
  if (spec.kernel == BlurKernel::Gaussian && !(spec.sigma > 0.0f)) {
    throw Error("Gaussian sigma " + std::to_string(spec.sigma) + " must be positive");
  }
  const int kernel = blurKernelId(spec.kernel);
  std::vector<float> weights;
  for (int i = -spec.radius; i <= spec.radius; ++i) {
    weights.push_back(shaders::kernelWeight1D(kernel, i, spec.radius, spec.sigma, 0.0f));
  }
  return weights;
}

std::vector<float> cumulativeBlurWeights(const BlurSpec& spec) {
  std::vector<float> sums = blurWeights(spec);
  for (size_t i = 1; i < sums.size(); ++i) sums[i] += sums[i - 1];
  return sums;
}

Image separableFilter(const Image& image, const BlurSpec& spec,
                      std::span<const ChannelReduction> reductions, float logExponent,
                      AlikeTaps alike) {
  checkReductions(image, reductions);
  Image horizontal = filterPass(image, spec, true, reductions, logExponent, alike);
  return filterPass(horizontal, spec, false, reductions, logExponent, alike);
}

Image separableFilterPass(const Image& image, const BlurSpec& spec, bool horizontal,
                          std::span<const ChannelReduction> reductions, float logExponent,
                          AlikeTaps alike) {
  checkReductions(image, reductions);
  return filterPass(image, spec, horizontal, reductions, logExponent, alike);
}

Image boxBlur(const Image& image, int radius) {
  return separableFilter(image, {BlurKernel::Box, radius, 1.0f});
}

Image gaussianBlur(const Image& image, int radius, float sigma) {
  return separableFilter(image, {BlurKernel::Gaussian, radius, sigma});
}

Image minFilter(const Image& image, int radius) {
  std::vector<ChannelReduction> r(size_t(image.channels()), ChannelReduction::Min);
  return separableFilter(image, {BlurKernel::Box, radius, 1.0f}, r);
}

Image maxFilter(const Image& image, int radius) {
  std::vector<ChannelReduction> r(size_t(image.channels()), ChannelReduction::Max);
  return separableFilter(image, {BlurKernel::Box, radius, 1.0f}, r);
}

Image reduceMipLevel(const Image& image, std::span<const ChannelReduction> reductions,
                     float logExponent) {
  checkReductions(image, reductions);
  const int w = shaders::mipLevelSize(image.width(), 1);
  const int h = shaders::mipLevelSize(image.height(), 1);
  Image out(w, h, image.channels());
  detail::parallelForRows(h, [&](int y) {
    const glm::ivec2 ys = shaders::mipSourceSpan(y, h, image.height());
    const int y0 = ys.x, y1 = ys.y;
    for (int x = 0; x < w; ++x) {
      const glm::ivec2 xs = shaders::mipSourceSpan(x, w, image.width());
      const int x0 = xs.x, x1 = xs.y;
      const float weight = 1.0f / float((x1 - x0 + 1) * (y1 - y0 + 1));
      for (int c = 0; c < image.channels(); ++c) {
        auto acc = startReduction(reductionOf(reductions, c), logExponent);
        for (int sy = y0; sy <= y1; ++sy) {
          for (int sx = x0; sx <= x1; ++sx)
            acc = shaders::accumulateTap(acc, image.at(sx, sy, c), weight);
        }
        out.at(x, y, c) = shaders::reductionResult(acc);
      }
    }
  });
  return out;
}

std::vector<Image> buildMipChain(const Image& image, std::span<const ChannelReduction> reductions,
                                 float logExponent) {
  std::vector<Image> chain{image};
  while (chain.back().width() > 1 || chain.back().height() > 1) {
    chain.push_back(reduceMipLevel(chain.back(), reductions, logExponent));
  }
  return chain;
}

}  // namespace penumbra
