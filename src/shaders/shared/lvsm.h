// Layered variance shadow maps (thesis §4.1): per-layer linear warps with overlap, one layer
// sampled per fragment, and a transition blend with the next layer near its upper split.
#ifndef PENUMBRA_SHARED_LVSM_H
#define PENUMBRA_SHARED_LVSM_H
#include "chebyshev.h"
#include "constants.h"
#include "layers.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct LvsmParams {
  float overlap;         // delta of thesis §4.1.1 in depth units, [0, 0.1]
  float transition;      // blend width below each split in depth units, [0, overlap]; 0 disables
  float minVariance;     // variance floor in the layer's warped depth^2 (not scaled back to
                         // linear depth: value * width^2 there), [0, 0.01]
  float bleedReduction;  // thesis §3.4 clamp, [0, 0.99]
  int storage;           // kStorageUnorm16 (thesis) or kStorageFloat32
  int placement;         // kLayerPlacementLloyd (thesis results), Uniform, or Fixed (`splits`)
  int lloydIterations;   // Lloyd relaxation steps per still image, [1, 64]
  int pad0;
  LayerSplits splits;  // the splits in use; the renderer replaces them when placement is Lloyd
};

PENUMBRA_INLINE LvsmParams lvsmDefaultParams() {
  LvsmParams p;
  p.overlap = 0.01f;
  p.transition = 0.005f;
  p.minVariance = 0.00001f;
  p.bleedReduction = 0.0f;
  p.storage = kStorageUnorm16;
  p.placement = kLayerPlacementLloyd;
  p.lloydIterations = 16;
  p.pad0 = 0;
  p.splits = uniformLayerSplits(4);
  return p;
}

PENUMBRA_INLINE vec2 lvsmLayerRange(int layer, LvsmParams p) {
  return overlappedLayerRange(p.splits, layer, p.overlap);
}

// The ranges LVSM's texel layer `texelLayer` encodes into: its two layers' (lvsmLayerRange),
// the last layer's again past the last, as (lower, upper, lower, upper). Splits and overlap
// apart, for the Lloyd step that writes them for splits it placed (passes/lloyd_step.comp).
PENUMBRA_INLINE vec4 lvsmTexelLayerRanges(int texelLayer, LayerSplits splits, float overlap) {
  int last = splits.layerCount - 1;
  vec2 a = overlappedLayerRange(splits, min(2 * texelLayer, last), overlap);
  vec2 b = overlappedLayerRange(splits, min(2 * texelLayer + 1, last), overlap);
  return vec4(a.x, a.y, b.x, b.y);
}

// The layer warp of thesis eq. 4.2: 0 in front of the layer, 1 behind it, linear inside.
PENUMBRA_INLINE float lvsmWarp(float depth, vec2 range) {
  return clamp((depth - range.x) / (range.y - range.x), 0.0f, 1.0f);
}

// Warped moments of a depth for the layer over `range` (lvsmLayerRange); two unorm16 channels
// per layer hold them.
PENUMBRA_INLINE vec2 lvsmEncodeInRange(float depth, vec2 range) {
  float w = lvsmWarp(depth, range);
  return vec2(w, w * w);
}

PENUMBRA_INLINE float lvsmLayerVisibility(vec2 moments, float receiverDepth, int layer,
                                          LvsmParams p) {
  float t = lvsmWarp(receiverDepth, lvsmLayerRange(layer, p));
  return reduceLightBleeding(chebyshevUpperBound(moments, t, p.minVariance), p.bleedReduction);
}

// Weight of the next layer for a receiver near the top of its layer, smooth over `transition`.
PENUMBRA_INLINE float lvsmTransitionWeight(float receiverDepth, int layer, LvsmParams p) {
  if (layer >= p.splits.layerCount - 1 || p.transition <= 0.0f) return 0.0f;
  float split = layerSplit(p.splits, layer + 1);
  return smoothstep(split - p.transition, split, receiverDepth);
}

// Visibility from the moments of the receiver's layer and of the layer above it.
PENUMBRA_INLINE float lvsmVisibility(vec2 layerMoments, vec2 nextLayerMoments, float receiverDepth,
                                     LvsmParams p) {
  int layer = selectLayer(receiverDepth, p.splits);
  float v = lvsmLayerVisibility(layerMoments, receiverDepth, layer, p);
  float w = lvsmTransitionWeight(receiverDepth, layer, p);
  if (w > 0.0f) {
    v = mix(v, lvsmLayerVisibility(nextLayerMoments, receiverDepth, layer + 1, p), w);
  }
  return v;
}

PENUMBRA_END_SHARED
#endif
