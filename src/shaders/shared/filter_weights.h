// Filter weights shared by the prefilter passes, PCF lookups and the CPU reference filters.
#ifndef PENUMBRA_SHARED_FILTER_WEIGHTS_H
#define PENUMBRA_SHARED_FILTER_WEIGHTS_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// The widest prefilter: 2 * 64 + 1 = 129 taps per axis (the passes' weight arrays hold them).
const int kMaxBlurRadius = 64;

const int kKernelBox = 0;
const int kKernelGaussian = 1;
const int kKernelBilinear = 2;          // box of 2r+1 texels convolved with the bilinear tent
const int kKernelGaussianBilinear = 3;  // Gaussian of 2r+1 taps convolved with the bilinear tent

// Kernels convolved with the bilinear tent: taps -r..r+1 around floor(position - 1/2).
PENUMBRA_INLINE bool kernelHasBilinearTent(int kernel) {
  return kernel == kKernelBilinear || kernel == kKernelGaussianBilinear;
}

// Whether every tap of the kernel weighs the same (the box: 1 / (2r + 1) each).
PENUMBRA_INLINE bool kernelTapsAlike(int kernel) {
  return kernel == kKernelBox;
}

// Unnormalised Gaussian weight of a tap `offset` texels from the centre.
PENUMBRA_INLINE float gaussianTapWeight(int offset, float sigma) {
  float x = float(offset);
  return exp(-(x * x) / (2.0f * sigma * sigma));
}

// Sum of the Gaussian taps -radius..radius, to normalise them to a unit sum.
PENUMBRA_INLINE float gaussianWeightSum(int radius, float sigma) {
  float sum = 0.0f;
  for (int i = -radius; i <= radius; ++i) {
    sum += gaussianTapWeight(i, sigma);
  }
  return sum;
}

// Normalised 1D weight of tap `tap` of a kernel of `radius` (2r+1 taps; the bilinear kernel has
// taps -r..r+1 and `fraction` is the lookup's sub-texel position in [0,1)). Taps outside the kernel
// weigh 0. 2D kernels are the product of two 1D weights.
// `gaussianSum` is gaussianWeightSum(radius, sigma) for the Gaussian (ignored otherwise): loops
// over taps compute it once (kernelWeight1D computes it per call).
PENUMBRA_INLINE float kernelWeight1DWithSum(int kernel, int tap, int radius, float sigma,
                                            float fraction, float gaussianSum) {
  float width = float(2 * radius + 1);
  if (kernel == kKernelGaussianBilinear) {
    // The tent's two taps (1 - f at t, f at t - 1) spread over the Gaussian's.
    float at = tap >= -radius && tap <= radius ? gaussianTapWeight(tap, sigma) : 0.0f;
    float before =
        tap - 1 >= -radius && tap - 1 <= radius ? gaussianTapWeight(tap - 1, sigma) : 0.0f;
    return ((1.0f - fraction) * at + fraction * before) / gaussianSum;
  }
  if (kernel == kKernelGaussian) {
    if (tap < -radius || tap > radius) return 0.0f;
    return gaussianTapWeight(tap, sigma) / gaussianSum;
  }
  if (kernel == kKernelBilinear) {
    if (tap < -radius || tap > radius + 1) return 0.0f;
    if (tap == -radius) return (1.0f - fraction) / width;
    if (tap == radius + 1) return fraction / width;
    return 1.0f / width;
  }
  if (tap < -radius || tap > radius) return 0.0f;
  return 1.0f / width;
}

PENUMBRA_INLINE float kernelWeight1D(int kernel, int tap, int radius, float sigma, float fraction) {
  bool gaussian = kernel == kKernelGaussian || kernel == kKernelGaussianBilinear;
  float gaussianSum = gaussian ? gaussianWeightSum(radius, sigma) : 1.0f;
  return kernelWeight1DWithSum(kernel, tap, radius, sigma, fraction, gaussianSum);
}

PENUMBRA_END_SHARED
#endif
