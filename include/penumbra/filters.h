// CPU reference filters: the prefilter passes the GPU runs, written for clarity and checked
// against brute force. Borders clamp to the edge; channels reduce by their ChannelReduction
// (mean channels are averaged, min/max channels take the min/max over the same footprint).
#pragma once

#include <span>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/technique.h"

namespace penumbra {

enum class BlurKernel { Box, Gaussian };

struct BlurSpec {
  BlurKernel kernel = BlurKernel::Gaussian;
  int radius = 2;      // (2r+1) taps per axis, r in [0, 64]
  float sigma = 1.0f;  // Gaussian standard deviation in texels, > 0
};

// The shared headers' id of the kernel (shared/filter_weights.h kKernelBox, kKernelGaussian).
int blurKernelId(BlurKernel kernel);

// The normalised 1D weights of the kernel, 2r+1 values (shared/filter_weights.h).
std::vector<float> blurWeights(const BlurSpec& spec);
// Running sums of blurWeights in tap order (2r+1 values, the last one their total): the filtered
// reference's blur, summed over a mip texel's block in closed form (shared/filtered_reference.h).
std::vector<float> cumulativeBlurWeights(const BlurSpec& spec);

// How a kernel whose taps all weigh alike (the box) sums them. SummedThenScaled adds every tap
// at unit weight and multiplies the total once by the common weight, as the GPU's prefilter does
// (shared/channel_reduction.h scaleTapWeights): one multiply per texel instead of one per tap.
// Weighted weighs each tap: for channels of exponentials (ESM filtering linearly, the EVSMs),
// whose unit-weight sum of up to 129 taps could pass fp32's largest value (3 exp(88) does).
enum class AlikeTaps { SummedThenScaled, Weighted };
AlikeTaps alikeTapsFor(Technique technique, const TechniqueParams& params);
// Whether the kernel's taps weigh alike (shared/filter_weights.h kernelTapsAlike) and are summed
// at unit weight under `alike`.
bool sumsTapsAtUnitWeight(const BlurSpec& spec, AlikeTaps alike);

// Separable filter over every channel. `reductions` gives one entry per channel (empty: all
// Mean). Min and Max channels take the extreme over the kernel's support; LogMeanExp channels
// (ESM log space) take the weighted log-mean-exp with exponent `logExponent`.
Image separableFilter(const Image& image, const BlurSpec& spec,
                      std::span<const ChannelReduction> reductions = {}, float logExponent = 80.0f,
                      AlikeTaps alike = AlikeTaps::SummedThenScaled);

// One axis of separableFilter (horizontal: along x), as the GPU's blur runs it: the renderer
// stores the intermediate in the channels' format, so its CPU twin rounds between the axes.
Image separableFilterPass(const Image& image, const BlurSpec& spec, bool horizontal,
                          std::span<const ChannelReduction> reductions = {},
                          float logExponent = 80.0f, AlikeTaps alike = AlikeTaps::SummedThenScaled);

Image boxBlur(const Image& image, int radius);
Image gaussianBlur(const Image& image, int radius, float sigma);
Image minFilter(const Image& image, int radius);
Image maxFilter(const Image& image, int radius);

// One mip level down: each texel reduces the 2x2 block below it (floor(w/2) x floor(h/2),
// at least 1; with an odd source size the last texel also takes the leftover row/column).
Image reduceMipLevel(const Image& image, std::span<const ChannelReduction> reductions = {},
                     float logExponent = 80.0f);
// The whole chain, level 0 (the image) down to 1x1.
std::vector<Image> buildMipChain(const Image& image,
                                 std::span<const ChannelReduction> reductions = {},
                                 float logExponent = 80.0f);

}  // namespace penumbra
