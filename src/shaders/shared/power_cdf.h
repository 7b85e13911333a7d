// The power-function CDF method (Gumbau et al. 2011): the occluder depth CDF over the filter
// region is fitted with t^beta from the filtered min, max and mean, and visibility follows eq. 4.
// The layered variant clamps depths into each layer's interval, widened by an overlap as LVSM's
// layers are (thesis §4.1.1): without it a sloped receiver just below a split sees its own far
// side clamped onto the split and darkens.
#ifndef PENUMBRA_SHARED_POWER_CDF_H
#define PENUMBRA_SHARED_POWER_CDF_H
#include "constants.h"
#include "layers.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// beta is kept in [1e-6, 1e6]: both ends are degenerate distributions where eq. 4 is 0/0.
const float kPowerCdfMinBeta = 0.000001f;
const float kPowerCdfMaxBeta = 1000000.0f;

struct PowerCdfParams {
  int storage;      // kStorageFloat32 or kStorageFloat16 (Gumbau §4: 16 bits suffice)
  float depthBias;  // subtracted from the receiver depth, [0, 0.1]: a planar receiver sits at
                    // the filtered mean, and storage rounding must not push it behind (eq. 1)
  float overlap;    // layer intervals widened by this on the inner sides, [0, 0.1] (layered)
  int pad2;
  LayerSplits splits;  // one layer is the paper's method; more is its layered variant
};

PENUMBRA_INLINE PowerCdfParams powerCdfDefaultParams() {
  PowerCdfParams p;
  p.storage = kStorageFloat32;
  p.depthBias = 0.001f;
  p.overlap = 0.01f;
  p.pad2 = 0;
  p.splits = uniformLayerSplits(1);
  return p;
}

PENUMBRA_INLINE vec2 powerCdfLayerRange(int layer, PowerCdfParams p) {
  return overlappedLayerRange(p.splits, layer, p.overlap);
}

// Depth clamped into a layer's overlapped interval `range`: occluders in front pile up at its
// lower end. A layer's (min, max, mean) channels all encode this depth; they are filtered with
// min, max and mean reductions.
PENUMBRA_INLINE float powerCdfDepthInRange(float depth, vec2 range) {
  return clamp(depth, range.x, range.y);
}

PENUMBRA_INLINE float powerCdfLayerDepth(float depth, int layer, PowerCdfParams p) {
  return powerCdfDepthInRange(depth, powerCdfLayerRange(layer, p));
}

// Gumbau eq. 3: the exponent that makes the mean of t^beta match the filtered mean.
PENUMBRA_INLINE float powerCdfBeta(float minDepth, float maxDepth, float meanDepth) {
  float beta = (meanDepth - minDepth) / max(maxDepth - meanDepth, 1.0e-30f);
  return clamp(beta, kPowerCdfMinBeta, kPowerCdfMaxBeta);
}

// 1 - exp(x) without the cancellation of the direct form when |x| is small.
PENUMBRA_INLINE float oneMinusExp(float x) {
  if (abs(x) < 0.01f) return -x * (1.0f + x * (0.5f + x / 6.0f));
  return 1.0f - exp(x);
}

// Gumbau eq. 4: (1 - t^beta) / (1 - (beta/(beta+1))^beta) for t beyond the mean, else 1.
PENUMBRA_INLINE float powerCdfVisibilityFromStats(vec3 minMaxMean, float receiverDepth) {
  float minDepth = minMaxMean.x;
  float maxDepth = minMaxMean.y;
  float meanDepth = minMaxMean.z;
  if (receiverDepth <= meanDepth) return 1.0f;
  float range = maxDepth - minDepth;
  if (range <= 0.0f) return 0.0f;  // a single depth, and the receiver lies behind it
  float t = (receiverDepth - minDepth) / range;
  if (t >= 1.0f) return 0.0f;
  float beta = powerCdfBeta(minDepth, maxDepth, meanDepth);
  float tMean = beta / (beta + 1.0f);
  float lit = oneMinusExp(beta * log(t));
  float litAtMean = oneMinusExp(beta * log(tMean));
  return clamp(lit / litAtMean, 0.0f, 1.0f);
}

// The layer whose statistics decide a receiver: the one holding its biased depth.
PENUMBRA_INLINE int powerCdfReceiverLayer(float receiverDepth, PowerCdfParams p) {
  return selectLayer(receiverDepth - p.depthBias, p.splits);
}

// Visibility from the statistics of the receiver's layer.
PENUMBRA_INLINE float powerCdfVisibility(vec3 layerMinMaxMean, float receiverDepth,
                                         PowerCdfParams p) {
  float biased = receiverDepth - p.depthBias;
  int layer = powerCdfReceiverLayer(receiverDepth, p);
  float z = powerCdfLayerDepth(biased, layer, p);
  return powerCdfVisibilityFromStats(layerMinMaxMean, z);
}

PENUMBRA_END_SHARED
#endif
