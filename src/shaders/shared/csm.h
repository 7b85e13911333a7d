// Convolution shadow maps (CSM paper §3): the step H(z - d) expanded in a truncated Fourier
// series of M terms whose sin/cos basis images of the depth z are filtered linearly.
#ifndef PENUMBRA_SHARED_CSM_H
#define PENUMBRA_SHARED_CSM_H
#include "constants.h"
#include "prelude.h"
#include "sin_cos_pi.h"
PENUMBRA_BEGIN_SHARED

const int kCsmMaxTerms = 16;

struct CsmParams {
  int termCount;      // M in [1, 16]; M/2 RGBA textures (CSM paper §4)
  float attenuation;  // alpha of the ringing attenuation exp(-alpha (k/M)^2) (§3.2.1), [0, 20]
  float offsetScale;  // receiver offset in units of 1/(2M) (§3.2.2), [0, min(4, M - 1)]; 1 puts
                      // the first ringing maximum on a lit receiver so lit surfaces come out lit
  float scale;        // the reconstruction is multiplied by this (§3.2.2: 2), [1, 4]
  int storage;        // kStorageUnorm8 (paper), kStorageFloat16 or kStorageFloat32
  int pad0;
  int pad1;
  int pad2;
};

PENUMBRA_INLINE CsmParams csmDefaultParams() {
  CsmParams p;
  p.termCount = 16;
  p.attenuation = 1.0f;
  p.offsetScale = 1.0f;
  p.scale = 1.0f;
  p.storage = kStorageUnorm8;
  p.pad0 = 0;
  p.pad1 = 0;
  p.pad2 = 0;
  return p;
}

// The plain truncated series of eq. 10-11 with M terms: no attenuation, offset or scaling, fp32
// basis (the curves of CSM Fig. 3(a) and the series' own tests).
PENUMBRA_INLINE CsmParams csmPlainSeriesParams(int termCount) {
  CsmParams p = csmDefaultParams();
  p.termCount = termCount;
  p.attenuation = 0.0f;
  p.offsetScale = 0.0f;
  p.scale = 1.0f;
  p.storage = kStorageFloat32;
  return p;
}

// c_k = pi (2k - 1), k = 1..M (CSM eq. 11).
PENUMBRA_INLINE float csmFrequency(int k) {
  return kPi * float(2 * k - 1);
}

// The expansion is a square wave of period 2 in t = z - d (eq. 10), a step only for |t| < 1, and
// its ringing spreads each jump over about 1/(2M). Depths in [0,1] are scaled by kappa before
// the expansion so that t plus the receiver offset stays clear of the jumps at t = +-1 for every
// pair of depths (the paper uses kappa = 1 and gets the wrong answer for receivers near the
// light with occluders near the far plane). The cost: the step is kappa times less steep. The
// registry keeps offset <= M - 1, so kappa >= 1/2 and the floor never binds for valid parameters.
PENUMBRA_INLINE float csmDepthScale(CsmParams p) {
  return max(0.5f, 1.0f - (1.0f + p.offsetScale) / (2.0f * float(p.termCount)));
}

// The basis images by Chebyshev's recurrence: texture t holds the terms k = 2t + 1 and 2t + 2,
// whose frequencies c_k are 4 pi apart from texture to texture, so with theta = 4 pi z each
// component follows sin((n + 1) theta + phi) = 2 cos(theta) sin(n theta + phi) - sin((n - 1) theta
// + phi) (and likewise cosine): one multiply-add per value and texture, from one sine and cosine
// of c_1 z and the multiple-angle identities. Evaluating each term directly takes 2M sines and
// cosines per texel (32 at M = 16: CSM's encode took 3.3x a copy of its textures on llvmpipe,
// 1.9x with the terms by rotation; docs/results/passes-llvmpipe-2026-12-01.md). Accuracy: see
// docs/techniques.md and Csm.BasisRecurrenceStaysWithinItsRoundingOfTheDirectBasis.
struct CsmBasisWalk {
  vec4 terms;          // texture t's (sin c_k z, cos c_k z, sin c_k+1 z, cos c_k+1 z), k = 2t + 1
  vec4 previous;       // texture t - 1's (before texture 0: the frequencies -3 pi and -pi)
  float twiceCosStep;  // 2 cos(4 pi z)
};

// The walk at texture 0 for a scaled depth z (csmDepthScale times the linear depth).
PENUMBRA_INLINE CsmBasisWalk csmBasisWalk(float z) {
  vec2 first = sinCosPi(z);  // c_1 = pi
  float s = first[0];
  float c = first[1];
  float cc = c * c;
  // Each value the walk keeps is precise, as sinCosPi's: the GPU rounds as the C++ build does.
  PENUMBRA_PRECISE float s3 = s * (4.0f * cc - 1.0f);  // sin 3a = sin a (4 cos^2 a - 1)
  PENUMBRA_PRECISE float c3 = c * (4.0f * cc - 3.0f);  // cos 3a = cos a (4 cos^2 a - 3)
  CsmBasisWalk w;
  w.terms = vec4(s, c, s3, c3);
  w.previous = vec4(-s3, c3, -s, c);
  // The step 2 cos 4a (a = pi z) by double angles, in the form whose error carried from cos 2a
  // or sin 2a vanishes where the recurrence magnifies it. An error e in cos 4a changes the
  // walk's frequency by e / |sin 4a|: at sin 4a = 0 it grows with the square of the steps instead
  // (7^2 e). 2 cos^2 2a - 1 carries cos 2a's rounding d times 4 |cos 2a|, 1 - 2 sin^2 2a sin 2a's
  // times 4 |sin 2a|; the first, where |cos 2a| < |sin 2a|, is within 4 |cos 2a| d <=
  // 2 sqrt(2) |sin 4a| d (sin 4a = 2 sin 2a cos 2a), the second likewise, so the carried error
  // moves the frequency by at most 2 sqrt(2) d anywhere. What stays is the step's own last
  // rounding, as with any float step. Against sin and cos in double over 200001 depths: 4.3e-6;
  // 3.9e-6 with the step by its own sinCosPi, which cost CSM's encode about 3 ms more on llvmpipe
  // (docs/results/passes-llvmpipe-2026-12-07/csm-encode-experiments.txt); cos^2 2a - sin^2 2a
  // everywhere, whose carried error stays where sin 4a = 0, 1.9e-5 on the test's grid.
  float c2 = (c - s) * (c + s);  // cos 2a
  float s2 = 2.0f * s * c;       // sin 2a
  PENUMBRA_PRECISE float step = c2 * c2 < s2 * s2 ? 4.0f * c2 * c2 - 2.0f : 2.0f - 4.0f * s2 * s2;
  w.twiceCosStep = step;
  return w;
}

PENUMBRA_INLINE CsmBasisWalk csmBasisWalkStart(float depth, CsmParams p) {
  return csmBasisWalk(csmDepthScale(p) * depth);
}

// The walk one texture on.
PENUMBRA_INLINE CsmBasisWalk csmBasisWalkNext(CsmBasisWalk w) {
  CsmBasisWalk next;
  PENUMBRA_PRECISE vec4 terms = w.twiceCosStep * w.terms - w.previous;
  next.terms = terms;
  next.previous = w.terms;
  next.twiceCosStep = w.twiceCosStep;
  return next;
}

// The walk's basis texture (eq. 14), mapped from [-1,1] to [0,1] so that unorm8 storage holds it;
// the map is affine, so filtering commutes. The recurrence's roundings may carry a mapped value
// past [0, 1], by at most its 5e-6 from the exact basis (Csm.BasisRecurrence...). Not clamped:
// unorm storage clamps as it converts, and float storage keeps a value that close as the basis
// it is; a clamp here was a third of the encode's arithmetic per value (docs/techniques.md, CSM).
PENUMBRA_INLINE vec4 csmBasisTexture(CsmBasisWalk w) {
  PENUMBRA_PRECISE vec4 mapped = w.terms * 0.5f + vec4(0.5f);
  return mapped;
}

// Basis texture `index` alone (terms 2 index + 1 and 2 index + 2), by the same walk as the
// encode's over every texture, so both give the same values.
PENUMBRA_INLINE vec4 csmEncodeTexture(float depth, int index, CsmParams p) {
  CsmBasisWalk w = csmBasisWalkStart(depth, p);
  for (int i = 0; i < index; ++i) w = csmBasisWalkNext(w);
  return csmBasisTexture(w);
}

PENUMBRA_INLINE int csmTextureCount(CsmParams p) {
  return (p.termCount + 1) / 2;
}

PENUMBRA_INLINE float csmAttenuationFactor(int k, CsmParams p) {
  float x = float(k) / float(p.termCount);
  return exp(-p.attenuation * x * x);
}

// The offset subtracted from the scaled receiver depth: the truncated wave first peaks at 1/(2M).
PENUMBRA_INLINE float csmReceiverOffset(CsmParams p) {
  return p.offsetScale / (2.0f * float(p.termCount));
}

// The truncated series f(d, z) = 1/2 + sum_k 2/c_k [sin(c_k z) cos(c_k d) - cos(c_k z) sin(c_k d)]
// (eq. 11-13, the step oriented as visibility H(z - d)), attenuated and offset (§3.2), unclamped.
PENUMBRA_INLINE float csmSeries(vec4 filteredBasis[8], float receiverDepth, CsmParams p) {
  float d = csmDepthScale(p) * receiverDepth - csmReceiverOffset(p);
  // The receiver's terms by the encode's walk: at d = z each product cancels as exactly as the
  // stored basis allows.
  CsmBasisWalk w = csmBasisWalk(d);
  float f = 0.5f;
  for (int t = 0; t < csmTextureCount(p); ++t) {
    vec4 basis = 2.0f * filteredBasis[t] - vec4(1.0f);
    for (int j = 0; j < 2; ++j) {
      int k = 2 * t + 1 + j;
      if (k > p.termCount) break;
      float sinZ = basis[2 * j];
      float cosZ = basis[2 * j + 1];
      float term = sinZ * w.terms[2 * j + 1] - cosZ * w.terms[2 * j];
      f += csmAttenuationFactor(k, p) * (2.0f / csmFrequency(k)) * term;
    }
    w = csmBasisWalkNext(w);
  }
  return f;
}

// The series scaled and clamped to [0,1] (§3.2.2).
PENUMBRA_INLINE float csmVisibility(vec4 filteredBasis[8], float receiverDepth, CsmParams p) {
  return clamp(p.scale * csmSeries(filteredBasis, receiverDepth, p), 0.0f, 1.0f);
}

PENUMBRA_END_SHARED
#endif
