// Accumulates filter taps under a channel's reduction (shared/constants.h kReduce*), mirroring
// the CPU reference's Reducer in src/core/filters.cpp.
#ifndef PENUMBRA_LIB_CHANNEL_REDUCE_GLSL
#define PENUMBRA_LIB_CHANNEL_REDUCE_GLSL
#include "technique_block.glsl"

float reduceStart(int reduction) {
  if (reduction == kReduceMin) return 3.4e38f;
  if (reduction == kReduceMax) return -3.4e38f;
  return 0.0f;
}

float reduceAdd(int reduction, float acc, bool first, float value, float weight) {
  if (reduction == kReduceMin) return min(acc, value);
  if (reduction == kReduceMax) return max(acc, value);
  if (reduction == kReduceLogMeanExp) {
    if (weight <= 0.0f) return acc;
    float term = esmLogSpaceWeighted(value, weight, params.esm.exponent);
    return first ? term : esmLogSpaceAdd(acc, term, params.esm.exponent);
  }
  return acc + weight * value;
}

#endif
