// sin(pi x) and cos(pi x) by polynomials, for the encode passes that need a sine and cosine per
// texel: with GLSL's general sin and cos, CSM's encode by rotation took 95-101 ms on llvmpipe,
// 72-97 ms with these (2048^2, M = 16; docs/results/passes-llvmpipe-2026-12-02.md).
#ifndef PENUMBRA_SHARED_SIN_COS_PI_H
#define PENUMBRA_SHARED_SIN_COS_PI_H
#include "constants.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// (sin pi x, cos pi x) for any finite x below 2^22 in magnitude. x is reduced to r = x - n with
// n the nearest integer (exact in float: n is within 1/2 of x), where sin(pi x) = (-1)^n sin(pi r)
// and cos(pi x) = (-1)^n cos(pi r). With u = pi r in [-pi/2, pi/2] the Taylor series to u^11 and
// u^12 are alternating, so each is within its first omitted term of exact: u^13/13! <= 5.7e-8
// and u^14/14! <= 6.4e-9, below float's rounding of values near 1 (6e-8).
// Each series is summed in powers of w = u^2, w^2 and w^4 (Estrin's scheme), not by Horner's
// rule: a chain of 6-8 dependent operations instead of 12-13. A CPU's GL (llvmpipe) runs a
// texel's start of CSM's walk with little else to overlap it, so its cost is that chain's
// latency: by perf samples the encode's start fell from 0.12-0.14 of its copy's time to
// 0.06-0.09 (csm-encode-experiments.txt, U). The sine adds u w times the rest of its series
// to u, which rounds less than u times the whole series (1.9e-7 against sin in double, Horner's
// 2.0e-7; 2.3e-7 as u times the series).
PENUMBRA_INLINE vec2 sinCosPi(float x) {
  float n = floor(x + 0.5f);
  float u = kPi * (x - n);
  float w = u * u;
  float w2 = w * w;
  float w4 = w2 * w2;
  float s = (w * (1.0f / 120.0f) - 1.0f / 6.0f) + w2 * (w * (1.0f / 362880.0f) - 1.0f / 5040.0f) -
            w4 * (1.0f / 39916800.0f);
  s = u + (u * w) * s;
  float c = (1.0f - w * 0.5f) + w2 * (1.0f / 24.0f - w * (1.0f / 720.0f)) +
            w4 * ((1.0f / 40320.0f - w * (1.0f / 3628800.0f)) + w2 * (1.0f / 479001600.0f));
  float sign = 1.0f - 4.0f * (0.5f * n - floor(0.5f * n));  // (-1)^n
  // Precise here, not only where a caller's precise value reaches (GLSL does not carry it into
  // called functions): the GPU rounds as the C++ build does (RendererTest.EncodeBlurAndMips...).
  PENUMBRA_PRECISE vec2 sinCos = vec2(sign * s, sign * c);
  return sinCos;
}

PENUMBRA_END_SHARED
#endif
