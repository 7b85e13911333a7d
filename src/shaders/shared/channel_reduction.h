// How filter taps combine under a channel's reduction (constants.h kReduce*): mean channels take
// the weighted sum, min/max channels the extreme over the taps that carry weight, ESM's log-space
// channel the weighted log-mean-exp (Salvi). The one definition behind the GPU's encode, blur,
// mip and lookup passes and the CPU reference filters.
#ifndef PENUMBRA_SHARED_CHANNEL_REDUCTION_H
#define PENUMBRA_SHARED_CHANNEL_REDUCTION_H
#include "constants.h"
#include "esm.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct ChannelAccumulator {
  int reduction;
  float logExponent;  // c of the log-space reduction
  float value;        // sum, min or max (read through reductionResult)
  vec2 logSum;        // the log-space reduction's running (peak, scale): esm.h esmLogSum*
  int taps;           // taps with positive weight so far
};

PENUMBRA_INLINE ChannelAccumulator startReduction(int reduction, float logExponent) {
  ChannelAccumulator a;
  a.reduction = reduction;
  a.logExponent = logExponent;
  a.value = 0.0f;
  if (reduction == kReduceMin) a.value = 3.402823e38f;
  if (reduction == kReduceMax) a.value = -3.402823e38f;
  a.logSum = vec2(0.0f);
  a.taps = 0;
  return a;
}

// Adds one tap. A tap of weight <= 0 lies outside the kernel and changes nothing, for min and max
// too: a bilinear lookup exactly on a texel centre must not take the neighbour's extreme.
// Means add w t in order (PENUMBRA_PRECISE): with the weights compiled in, a compiler could
// otherwise regroup equal weights' products into w (t0 + t1 + ...), whose sum of exponentials
// passes fp32's range (blur.comp).
PENUMBRA_INLINE ChannelAccumulator accumulateTap(ChannelAccumulator a, float value, float weight) {
  if (weight <= 0.0f) return a;
  if (a.reduction == kReduceMin) {
    a.value = min(a.value, value);
  } else if (a.reduction == kReduceMax) {
    a.value = max(a.value, value);
  } else if (a.reduction == kReduceLogMeanExp) {
    a.logSum = a.taps == 0 ? esmLogSumStart(value, weight)
                           : esmLogSumAdd(a.logSum, value, weight, a.logExponent);
  } else {
    PENUMBRA_PRECISE float total = a.value + weight * value;
    a.value = total;
  }
  a.taps = a.taps + 1;
  return a;
}

// One tap of a texel layer whose channels all reduce as means: the weighted sum of whole texels,
// the accumulateTap arithmetic of a mean channel on four at once. The prefilter passes take this
// path where every channel is a mean (decided on the CPU, reductionDefines) so that llvmpipe's
// masked execution does not run the other reductions' branches for every tap. In order, as
// accumulateTap's.
PENUMBRA_INLINE vec4 accumulateMeanTexel(vec4 sum, vec4 texel, float weight) {
  PENUMBRA_PRECISE vec4 total = sum + weight * texel;
  return total;
}
// The same for a texel of two or one components (the fused prefilter keeps only the format's).
PENUMBRA_INLINE vec2 accumulateMeanTexel(vec2 sum, vec2 texel, float weight) {
  PENUMBRA_PRECISE vec2 total = sum + weight * texel;
  return total;
}
PENUMBRA_INLINE float accumulateMeanTexel(float sum, float texel, float weight) {
  PENUMBRA_PRECISE float total = sum + weight * texel;
  return total;
}

// A kernel whose taps all weigh alike (the box): the passes add every tap at unit weight and
// scale the total once, (sum of t) w rather than the sum of w t: one multiply per texel where
// weighting each tap costs one per tap, the arithmetic of the plainest box blur (weighting each
// tap made the blur 1.26x it on llvmpipe; docs/results/passes-llvmpipe-2026-12-06-box.md). Scaling
// every weight by w scales a mean's sum and the log-space sum's scale alike (esmLogSumAdd is
// linear in the weights); min and max take no weights. The CPU reference filters do the same
// where the taps are summed so (sumsTapsAtUnitWeight, penumbra/filters.h): not for channels of
// exponentials, whose unit-weight sums could pass fp32's range.
PENUMBRA_INLINE ChannelAccumulator scaleTapWeights(ChannelAccumulator a, float weight) {
  if (a.reduction == kReduceMin || a.reduction == kReduceMax) return a;
  if (a.reduction == kReduceLogMeanExp) {
    a.logSum.y = a.logSum.y * weight;
  } else {
    a.value = a.value * weight;
  }
  return a;
}
// The same for a texel layer of means (accumulateMeanTexel).
PENUMBRA_INLINE vec4 scaleMeanTexel(vec4 sum, float weight) {
  return sum * weight;
}
PENUMBRA_INLINE vec2 scaleMeanTexel(vec2 sum, float weight) {
  return sum * weight;
}
PENUMBRA_INLINE float scaleMeanTexel(float sum, float weight) {
  return sum * weight;
}

// The reduced value of the taps so far (0 before any tap).
PENUMBRA_INLINE float reductionResult(ChannelAccumulator a) {
  if (a.reduction == kReduceLogMeanExp) {
    return a.taps == 0 ? 0.0f : esmLogSumValue(a.logSum, a.logExponent);
  }
  return a.value;
}

PENUMBRA_END_SHARED
#endif
