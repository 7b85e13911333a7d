// The plain shadow-map depth test with constant and slope-scaled bias; also PCF's per-tap test.
#ifndef PENUMBRA_SHARED_HARD_H
#define PENUMBRA_SHARED_HARD_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct HardParams {
  float constantBias;     // light-space linear depth units, [0, 0.1]
  float slopeScaledBias;  // times the receiver's depth slope per shadow-map texel, [0, 10]
  float pad0;
  float pad1;
};

PENUMBRA_INLINE HardParams hardDefaultParams() {
  HardParams p;
  p.constantBias = 0.0005f;
  p.slopeScaledBias = 1.0f;
  p.pad0 = 0.0f;
  p.pad1 = 0.0f;
  return p;
}

// Receiver depth moved toward the light by the bias; depthSlope is |d depth / d texel| (0 when
// unknown).
PENUMBRA_INLINE float biasedReceiverDepth(float receiverDepth, float depthSlope, HardParams p) {
  return receiverDepth - p.constantBias - p.slopeScaledBias * depthSlope;
}

// 1 when the occluder depth is at or behind the (biased) receiver: thesis §2, shadow test step 2.
PENUMBRA_INLINE float hardVisibility(float occluderDepth, float biasedReceiver) {
  return biasedReceiver <= occluderDepth ? 1.0f : 0.0f;
}

PENUMBRA_END_SHARED
#endif
