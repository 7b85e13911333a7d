// Depth layers for the layered techniques (LVSM, layered power-CDF): L layers split [0,1] at
// L-1 increasing interior depths s_1..s_{L-1}; s_0 = 0 and s_L = 1 are implicit.
#ifndef PENUMBRA_SHARED_LAYERS_H
#define PENUMBRA_SHARED_LAYERS_H
#include "constants.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// How split depths are chosen (thesis §4.1.2).
const int kLayerPlacementUniform = 0;
const int kLayerPlacementLloyd = 1;  // weighted k-means on second-occluder depths, per frame
const int kLayerPlacementFixed = 2;  // the splits given

// Interior splits packed four to a vec4, so std140/std430 blocks and C++ share one layout.
struct LayerSplits {
  vec4 interior[4];  // s_1..s_15, increasing, in (0,1); entries past layerCount-2 are unused
  int layerCount;    // L in [1, kMaxLayers]
  int pad0;
  int pad1;
  int pad2;
};

// s_i for i in [0, L]: 0 below, 1 at the top, the interior split otherwise.
PENUMBRA_INLINE float layerSplit(LayerSplits splits, int i) {
  if (i <= 0) return 0.0f;
  if (i >= splits.layerCount) return 1.0f;
  int k = i - 1;
  return splits.interior[k / 4][k % 4];
}

PENUMBRA_INLINE LayerSplits uniformLayerSplits(int layerCount) {
  LayerSplits s;
  s.layerCount = layerCount;
  s.pad0 = 0;
  s.pad1 = 0;
  s.pad2 = 0;
  for (int k = 0; k < 4; ++k) {
    s.interior[k] = vec4(1.0f);
  }
  for (int k = 0; k < kMaxLayers - 1; ++k) {
    s.interior[k / 4][k % 4] = float(k + 1) / float(layerCount);
  }
  return s;
}

// The layer j with s_j <= depth < s_{j+1} (the top layer includes depth 1).
PENUMBRA_INLINE int selectLayer(float depth, LayerSplits splits) {
  int layer = 0;
  for (int i = 1; i < splits.layerCount; ++i) {
    if (depth >= layerSplit(splits, i)) layer = i;
  }
  return layer;
}

// [p_i, q_i] of layer i: its split interval widened by `overlap` on the inner sides (thesis
// §4.1.1), so that a receiver near a split still sees its own surface's depths inside the layer.
PENUMBRA_INLINE vec2 overlappedLayerRange(LayerSplits splits, int layer, float overlap) {
  float lower = layer == 0 ? 0.0f : layerSplit(splits, layer) - overlap;
  float upper = layer == splits.layerCount - 1 ? 1.0f : layerSplit(splits, layer + 1) + overlap;
  return vec2(max(lower, 0.0f), min(upper, 1.0f));
}

PENUMBRA_END_SHARED
#endif
