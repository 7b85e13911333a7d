// Chebyshev's one-tailed bound and light-bleeding reduction: the core of VSM, LVSM and EVSM.
#ifndef PENUMBRA_SHARED_CHEBYSHEV_H
#define PENUMBRA_SHARED_CHEBYSHEV_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// Upper bound on P(occluder >= t) from the first two moments (thesis eq. 3.2, 3.3). The variance
// is clamped to minVariance against numerical trouble; 1 when t is not beyond the mean.
PENUMBRA_INLINE float chebyshevUpperBound(vec2 moments, float t, float minVariance) {
  float mean = moments.x;
  if (t <= mean) return 1.0f;
  float variance = max(moments.y - mean * mean, minVariance);
  float distance = t - mean;
  return variance / (variance + distance * distance);
}

// Clamps away the bound's tail below `amount` and rescales the rest to [0,1] (thesis §3.4).
// It over-darkens penumbrae in exchange for less light bleeding; amount in [0, 0.99].
PENUMBRA_INLINE float reduceLightBleeding(float pMax, float amount) {
  return clamp((pMax - amount) / (1.0f - amount), 0.0f, 1.0f);
}

PENUMBRA_END_SHARED
#endif
