// Percentage-closer filtering (thesis ch. 2): the depth test per tap, then the kernel-weighted sum.
// The lookup loop lives with the texture access (GLSL lib / CPU reference); its parts live here.
#ifndef PENUMBRA_SHARED_PCF_H
#define PENUMBRA_SHARED_PCF_H
#include "filter_weights.h"
#include "hard.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct PcfParams {
  int kernel;         // kKernelBox, kKernelGaussian, kKernelBilinear or kKernelGaussianBilinear
  int radius;         // taps each side of the centre: (2r+1)^2 taps, r in [0, 64] like the blur
  float sigma;        // Gaussian standard deviation in texels, [0.01, 64] like the blur
  int receiverPlane;  // 1: each tap's receiver depth follows the receiver plane (bias)
  HardParams bias;
};

PENUMBRA_INLINE PcfParams pcfDefaultParams() {
  PcfParams p;
  p.kernel = kKernelBilinear;
  p.radius = 2;
  p.sigma = 1.0f;
  p.receiverPlane = 1;
  p.bias = hardDefaultParams();
  return p;
}

// The kernel's normalising sum, for pcfTapWeightWithSum: a lookup computes it once, not once per
// tap (the Gaussian's sum is a loop over the radius, O(r^3) per lookup if taken per tap; llvmpipe
// also ends all loops of a shader invocation after 65535 iterations, which r >= 16 exceeded).
PENUMBRA_INLINE float pcfKernelSum(PcfParams p) {
  bool gaussian = p.kernel == kKernelGaussian || p.kernel == kKernelGaussianBilinear;
  return gaussian ? gaussianWeightSum(p.radius, p.sigma) : 1.0f;
}

// Weight of tap (tapX, tapY) for a lookup whose sub-texel position is `fraction`.
PENUMBRA_INLINE float pcfTapWeightWithSum(int tapX, int tapY, vec2 fraction, PcfParams p,
                                          float kernelSum) {
  return kernelWeight1DWithSum(p.kernel, tapX, p.radius, p.sigma, fraction.x, kernelSum) *
         kernelWeight1DWithSum(p.kernel, tapY, p.radius, p.sigma, fraction.y, kernelSum);
}

PENUMBRA_INLINE float pcfTapWeight(int tapX, int tapY, vec2 fraction, PcfParams p) {
  return pcfTapWeightWithSum(tapX, tapY, fraction, p, pcfKernelSum(p));
}

// Lowest tap offset of the kernel; the highest is radius, or radius + 1 for the bilinear kernel.
PENUMBRA_INLINE int pcfFirstTap(PcfParams p) {
  return -p.radius;
}
PENUMBRA_INLINE int pcfLastTap(PcfParams p) {
  return kernelHasBilinearTent(p.kernel) ? p.radius + 1 : p.radius;
}

PENUMBRA_END_SHARED
#endif
