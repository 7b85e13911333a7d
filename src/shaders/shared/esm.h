// Exponential shadow maps (ESM paper §3; Salvi): the step approximated by exp(-c(d - z)), which
// factors into exp(c z) filtered over the kernel times exp(-c d). Linear-space filtering stores
// exp(c z) (c up to 88 in fp32); log-space filtering stores z and filters
// (1/c) ln sum w exp(c z) with the helpers below, finite for any c.
#ifndef PENUMBRA_SHARED_ESM_H
#define PENUMBRA_SHARED_ESM_H
#include "constants.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

const int kEsmFilterLinear = 0;
const int kEsmFilterLog = 1;

// Failure classification (ESM paper §3.3): where the planar-receiver assumption fails, the
// renderer shades the pixel with PCF instead (the fallback below).
const int kEsmClassifyNone = 0;
const int kEsmClassifyThreshold = 1;  // the filtered ESM value exceeds 1 + epsilon
const int kEsmClassifyZmax = 2;       // the max depth under the filter lies behind the receiver
// What a failing pixel is shaded with: PCF over the light pass's unfiltered depth with the
// prefilter's kernel (the default: it undoes the prefilter, which the paper's cannot), or the
// paper's 2x2 test on the prefiltered ESM texels (ESM paper §3.3, §3.4).
const int kEsmFallbackPcf = 0;
const int kEsmFallbackPaper = 1;
// exp(88) = 1.65e38 < FLT_MAX: the largest c whose exp(c z) fp32 stores for z in [0,1].
const float kEsmMaxLinearExponent = 88.0f;

struct EsmParams {
  float exponent;    // c: 80 for fp32 (ESM paper §3.2); (0, 88] linear, (0, 10000] log space
  int filterSpace;   // kEsmFilterLinear or kEsmFilterLog
  float threshold;   // epsilon of threshold classification (ESM paper §3.3), [0, 10]
  int classifier;    // kEsmClassifyNone, kEsmClassifyThreshold (the paper's choice) or Zmax
  float zmaxOffset;  // added to the receiver depth before the Z-max test (§3.3), [0, 0.1]
  int fallback;      // kEsmFallbackPcf or kEsmFallbackPaper
  float pad1;
  float pad2;
};

PENUMBRA_INLINE EsmParams esmDefaultParams() {
  EsmParams p;
  p.exponent = 80.0f;
  p.filterSpace = kEsmFilterLinear;
  p.threshold = 0.05f;
  p.classifier = kEsmClassifyThreshold;
  p.zmaxOffset = 0.005f;
  p.fallback = kEsmFallbackPcf;
  p.pad1 = 0.0f;
  p.pad2 = 0.0f;
  return p;
}

// The stored value: exp(c z) for linear-space filtering, z itself for log-space filtering.
PENUMBRA_INLINE float esmEncode(float depth, EsmParams p) {
  return p.filterSpace == kEsmFilterLog ? depth : exp(p.exponent * depth);
}

// Log-space filtering (Salvi). A log-space value v stands for exp(c v); a weighted sum of such
// terms is kept as (peak, scale): the largest value so far and sum_i w_i exp(c (v_i - peak)),
// which lies in (0, sum of weights], so nothing overflows for any c. One exp per term (the
// pairwise log-add it replaced took three transcendentals). Weights must be > 0.
PENUMBRA_INLINE vec2 esmLogSumStart(float value, float weight) {
  return vec2(value, weight);
}
// The exponential is taken once, of minus the distance to the new peak, before choosing which
// side it scales: as two branches each with its own exp, SIMD rasterisers (llvmpipe) evaluate
// both for every tap. The same bits either way: -(c |v - s|) is c (v - s) for v <= s and
// c (s - v) otherwise, the negations exact.
PENUMBRA_INLINE vec2 esmLogSumAdd(vec2 sum, float value, float weight, float exponent) {
  float scale = exp(-exponent * abs(value - sum.x));
  if (value <= sum.x) return vec2(sum.x, sum.y + weight * scale);
  return vec2(value, sum.y * scale + weight);
}
// The log-space value of the sum: ln(sum_i w_i exp(c v_i)) / c.
PENUMBRA_INLINE float esmLogSumValue(vec2 sum, float exponent) {
  return sum.x + log(sum.y) / exponent;
}

// ln of the filtered test exp(c (z - d)) summed over the kernel: ln E / exp(c d), where E is the
// filtered store. Positive values mean some occluder lies behind the receiver (paper §3.3).
PENUMBRA_INLINE float esmLogShadowTest(float filtered, float receiverDepth, EsmParams p) {
  if (p.filterSpace == kEsmFilterLog) return p.exponent * (filtered - receiverDepth);
  // Evaluated as a difference of logs: exp(-c d) alone underflows to a denormal near d = 1.
  return log(max(filtered, 1.0e-30f)) - p.exponent * receiverDepth;
}

// ESM paper eq. 3, clamped to 1 where the planar-receiver assumption fails.
PENUMBRA_INLINE float esmVisibility(float filtered, float receiverDepth, EsmParams p) {
  return exp(min(esmLogShadowTest(filtered, receiverDepth, p), 0.0f));
}

// Threshold classification (ESM paper §3.3): the unclamped ESM value exceeds 1 + epsilon.
PENUMBRA_INLINE bool esmFailsThreshold(float filtered, float receiverDepth, EsmParams p) {
  return esmLogShadowTest(filtered, receiverDepth, p) > log(1.0f + p.threshold);
}

// Z-max classification (ESM paper §3.3): some occluder under the filter lies behind the receiver
// (offset so that lit surfaces are not flagged), so exp(-c(d - z)) > 1 somewhere in the sum.
PENUMBRA_INLINE bool esmFailsZmax(float maxDepth, float receiverDepth, EsmParams p) {
  return maxDepth > receiverDepth + p.zmaxOffset;
}

PENUMBRA_END_SHARED
#endif
