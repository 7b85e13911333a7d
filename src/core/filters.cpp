// Separable blur, min/max filters and mip reduction over float images.
#include "penumbra/filters.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <string>

#include "parallel.h"
#include "penumbra/error.h"
#include "shared/esm.h"
#include "shared/filter_weights.h"

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

// Reduces taps (value, weight) one at a time; weights of a kernel sum to 1.
class Reducer {
 public:
  Reducer(ChannelReduction reduction, float logExponent)
      : reduction_(reduction), logExponent_(logExponent) {
    if (reduction == ChannelReduction::Min) acc_ = std::numeric_limits<float>::max();
    if (reduction == ChannelReduction::Max) acc_ = std::numeric_limits<float>::lowest();
  }

  void add(float value, float weight) {
    switch (reduction_) {
      case ChannelReduction::Mean: acc_ += weight * value; break;
      case ChannelReduction::Min: acc_ = std::min(acc_, value); break;
      case ChannelReduction::Max: acc_ = std::max(acc_, value); break;
      case ChannelReduction::LogMeanExp: {
        if (weight <= 0.0f) break;
        float term = shaders::esmLogSpaceWeighted(value, weight, logExponent_);
        acc_ = empty_ ? term : shaders::esmLogSpaceAdd(acc_, term, logExponent_);
        break;
      }
    }
    empty_ = false;
  }

  float result() const { return acc_; }

 private:
  ChannelReduction reduction_;
  float logExponent_;
  float acc_ = 0.0f;
  bool empty_ = true;
};

// One 1D pass along x (horizontal) or y with edge clamping.
Image filterPass(const Image& in, std::span<const float> weights, bool horizontal,
                 std::span<const ChannelReduction> reductions, float logExponent) {
  Image out(in.width(), in.height(), in.channels());
  const int radius = int(weights.size() / 2);
  detail::parallelForRows(in.height(), [&](int y) {
    for (int x = 0; x < in.width(); ++x) {
      for (int c = 0; c < in.channels(); ++c) {
        Reducer reducer(reductionOf(reductions, c), logExponent);
        for (int i = -radius; i <= radius; ++i) {
          float v = horizontal ? in.clamped(x + i, y, c) : in.clamped(x, y + i, c);
          reducer.add(v, weights[size_t(i + radius)]);
        }
        out.at(x, y, c) = reducer.result();
      }
    }
  });
  return out;
}

}  // namespace

std::vector<float> blurWeights(const BlurSpec& spec) {
  if (spec.radius < 0 || spec.radius > 64) {
    throw Error("blur radius " + std::to_string(spec.radius) + " is out of range [0, 64]");
  }
  if (spec.kernel == BlurKernel::Gaussian && !(spec.sigma > 0.0f)) {
    throw Error("Gaussian sigma " + std::to_string(spec.sigma) + " must be positive");
  }
  const int kernel =
      spec.kernel == BlurKernel::Box ? shaders::kKernelBox : shaders::kKernelGaussian;
  std::vector<float> weights;
  for (int i = -spec.radius; i <= spec.radius; ++i) {
    weights.push_back(shaders::kernelWeight1D(kernel, i, spec.radius, spec.sigma, 0.0f));
  }
  return weights;
}

Image separableFilter(const Image& image, const BlurSpec& spec,
                      std::span<const ChannelReduction> reductions, float logExponent) {
  checkReductions(image, reductions);
  const std::vector<float> weights = blurWeights(spec);
  Image horizontal = filterPass(image, weights, true, reductions, logExponent);
  return filterPass(horizontal, weights, false, reductions, logExponent);
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
  const int w = std::max(1, image.width() / 2);
  const int h = std::max(1, image.height() / 2);
  Image out(w, h, image.channels());
  // The source span of destination texel i: [2i, 2i+1], the last one extended to the edge.
  auto span = [](int i, int count, int source) {
    int first = std::min(2 * i, source - 1);
    int last = i == count - 1 ? source - 1 : 2 * i + 1;
    return std::pair{first, last};
  };
  detail::parallelForRows(h, [&](int y) {
    auto [y0, y1] = span(y, h, image.height());
    for (int x = 0; x < w; ++x) {
      auto [x0, x1] = span(x, w, image.width());
      const float weight = 1.0f / float((x1 - x0 + 1) * (y1 - y0 + 1));
      for (int c = 0; c < image.channels(); ++c) {
        Reducer reducer(reductionOf(reductions, c), logExponent);
        for (int sy = y0; sy <= y1; ++sy) {
          for (int sx = x0; sx <= x1; ++sx) reducer.add(image.at(sx, sy, c), weight);
        }
        out.at(x, y, c) = reducer.result();
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
