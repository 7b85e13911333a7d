// Percentage-closer filtering (thesis ch. 2): the depth test per tap, then the kernel-weighted sum.
// The lookup loop lives with the texture access (GLSL lib / CPU reference); its parts live here.
#ifndef PENUMBRA_SHARED_PCF_H
#define PENUMBRA_SHARED_PCF_H
#include "filter_weights.h"
#include "hard.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct PcfParams {
  int kernel;         // kKernelBox, kKernelGaussian or kKernelBilinear
  int radius;         // taps each side of the centre: (2r+1)^2 taps, r in [0, 15]
  float sigma;        // Gaussian standard deviation in texels, [0.25, 16]
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

// Weight of tap (tapX, tapY) for a lookup whose sub-texel position is `fraction`.
PENUMBRA_INLINE float pcfTapWeight(int tapX, int tapY, vec2 fraction, PcfParams p) {
  return kernelWeight1D(p.kernel, tapX, p.radius, p.sigma, fraction.x) *
         kernelWeight1D(p.kernel, tapY, p.radius, p.sigma, fraction.y);
}

// Lowest tap offset of the kernel; the highest is radius, or radius + 1 for the bilinear kernel.
PENUMBRA_INLINE int pcfFirstTap(PcfParams p) {
  return -p.radius;
}
PENUMBRA_INLINE int pcfLastTap(PcfParams p) {
  return p.kernel == kKernelBilinear ? p.radius + 1 : p.radius;
}

PENUMBRA_END_SHARED
#endif
