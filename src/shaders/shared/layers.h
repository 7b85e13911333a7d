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

// s_i for i in [0, L]: 0 below, 1 at the top, the interior split otherwise. The split is picked
// by selects over constant indices, not by a dynamic index: GLSL passes `splits` by value, and a
// dynamic index into that copy makes llvmpipe spill it to per-lane memory and gather from it —
// LVSM's encode took 7x a copy that way (docs/results/passes-llvmpipe-2026-12-01.md, issue 12).
PENUMBRA_INLINE float layerSplit(LayerSplits splits, int i) {
  int k = clamp(i - 1, 0, kMaxLayers - 2);
  int row = k / 4;
  int column = k - 4 * row;
  vec4 q = splits.interior[0];
  q = row == 1 ? splits.interior[1] : q;
  q = row == 2 ? splits.interior[2] : q;
  q = row == 3 ? splits.interior[3] : q;
  float interior = q[0];
  interior = column == 1 ? q[1] : interior;
  interior = column == 2 ? q[2] : interior;
  interior = column == 3 ? q[3] : interior;
  return i <= 0 ? 0.0f : (i >= splits.layerCount ? 1.0f : interior);
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
// The outer ends need no test: s_0 - overlap clamps to 0 and s_L + overlap to 1.
PENUMBRA_INLINE vec2 overlappedLayerRange(LayerSplits splits, int layer, float overlap) {
  float lower = layerSplit(splits, layer) - overlap;
  float upper = layerSplit(splits, layer + 1) + overlap;
  return vec2(max(lower, 0.0f), min(upper, 1.0f));
}

PENUMBRA_END_SHARED
#endif
