// Lloyd relaxation of layer splits (thesis §4.1.2), the parts the GPU's sample and sum passes and
// the CPU reference (src/core/layer_placement.cpp) share: the second-occluder sample of a 2x2
// texel block and the cluster a sample joins.
#ifndef PENUMBRA_SHARED_LAYER_PLACEMENT_H
#define PENUMBRA_SHARED_LAYER_PLACEMENT_H
#include "layers.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// Samples of weight at most this are flat footprints: no depth discontinuity to place a split at.
const float kMinSplitWeight = 0.000001f;

struct SecondOccluderSample {
  float depth;   // mu + sigma of the block: the farther depth when two depths share it
  float weight;  // sigma^2, zero for flat blocks and for blocks touching the empty far plane
};

// The sample of a 2x2 block of linear depths (thesis §4.1.2: "second occluder" mu + sigma,
// weighted by the variance). A block touching the cleared far plane (depth 1) is an edge against
// nothing and weighs nothing.
PENUMBRA_INLINE SecondOccluderSample secondOccluderSample(vec4 blockDepths) {
  float m1 = 0.0f;
  float m2 = 0.0f;
  bool empty = false;
  for (int i = 0; i < 4; ++i) {
    float z = blockDepths[i];
    m1 += 0.25f * z;
    m2 += 0.25f * z * z;
    empty = empty || z >= 1.0f;
  }
  PENUMBRA_PRECISE float variance = max(m2 - m1 * m1, 0.0f);
  SecondOccluderSample s;
  s.depth = m1 + sqrt(variance);
  s.weight = variance > kMinSplitWeight && !empty ? variance : 0.0f;
  return s;
}

// The cluster (interior split k, 0-based) nearest to `depth`, the first of equals.
PENUMBRA_INLINE int nearestSplit(LayerSplits splits, float depth) {
  int nearest = 0;
  for (int k = 1; k < splits.layerCount - 1; ++k) {
    if (abs(layerSplit(splits, k + 1) - depth) < abs(layerSplit(splits, nearest + 1) - depth)) {
      nearest = k;
    }
  }
  return nearest;
}

PENUMBRA_END_SHARED
#endif
