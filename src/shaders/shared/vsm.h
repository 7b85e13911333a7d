// Variance shadow maps (thesis ch. 3): store (z, z^2), filter linearly, bound with Chebyshev.
#ifndef PENUMBRA_SHARED_VSM_H
#define PENUMBRA_SHARED_VSM_H
#include "chebyshev.h"
#include "constants.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct VsmParams {
  float minVariance;     // variance floor in linear depth^2 units, [0, 0.01]
  float bleedReduction;  // thesis §3.4 clamp, [0, 0.99]; 0 disables it
  int storage;           // kStorageFloat32 or kStorageUnorm16
  float pad0;
};

PENUMBRA_INLINE VsmParams vsmDefaultParams() {
  VsmParams p;
  p.minVariance = 0.00001f;
  p.bleedReduction = 0.0f;
  p.storage = kStorageFloat32;
  p.pad0 = 0.0f;
  return p;
}

// The two moments of a linear depth in [0,1] (thesis eq. 3.1); both stay in [0,1].
PENUMBRA_INLINE vec2 vsmEncode(float depth) {
  return vec2(depth, depth * depth);
}

PENUMBRA_INLINE float vsmVisibility(vec2 moments, float receiverDepth, VsmParams p) {
  float pMax = chebyshevUpperBound(moments, receiverDepth, p.minVariance);
  return reduceLightBleeding(pMax, p.bleedReduction);
}

PENUMBRA_END_SHARED
#endif
