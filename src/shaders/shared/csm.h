// Convolution shadow maps (CSM paper §3): the step H(z - d) expanded in a truncated Fourier
// series of M terms whose sin/cos basis images of the depth z are filtered linearly.
#ifndef PENUMBRA_SHARED_CSM_H
#define PENUMBRA_SHARED_CSM_H
#include "constants.h"
#include "prelude.h"
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

// The basis images by angle addition: the frequencies step by c_{k+1} - c_k = 2 pi, so one sine
// and cosine of c_1 z and the double angle 2 pi z give every term by rotation, where evaluating
// each term directly takes 2M sines and cosines per texel (32 at M = 16: CSM's encode took 3.3x a
// copy, docs/results/passes-llvmpipe-2026-12-01.md). A wave holds (sin c_k z, cos c_k z) of the
// next texture's first term and (sin 2 pi z, cos 2 pi z) of the step. Each rotation adds a few
// float roundings; after the M - 1 = 15 rotations of M = 16 the terms stay within 7.3e-6 of
// exact, as close as evaluating each term in float (7.1e-6: the argument 31 pi z rounds;
// docs/techniques.md, Csm.WaveRecurrenceStaysWithinItsRoundingOfTheDirectBasis).
// The wave of the first term at a scaled depth z (csmDepthScale times the linear depth).
PENUMBRA_INLINE vec4 csmWave(float z) {
  float theta = csmFrequency(1) * z;
  float s = sin(theta);
  float c = cos(theta);
  return vec4(s, c, 2.0f * s * c, c * c - s * s);
}

PENUMBRA_INLINE vec4 csmWaveStart(float depth, CsmParams p) {
  return csmWave(csmDepthScale(p) * depth);
}

// The wave one term on: c_k z + 2 pi z.
PENUMBRA_INLINE vec4 csmWaveRotate(vec4 wave) {
  return vec4(wave[0] * wave[3] + wave[1] * wave[2], wave[1] * wave[3] - wave[0] * wave[2], wave[2],
              wave[3]);
}

// The wave's basis texture: terms k and k + 1 as (sin c_k z, cos c_k z, sin c_k+1 z,
// cos c_k+1 z) of the scaled depth (eq. 14), mapped from [-1,1] to [0,1] so that unorm8 storage
// holds them; the map is affine, so filtering commutes.
// The rotations' roundings may carry a term a few ulps past +-1: clamped, as unorm storage does.
PENUMBRA_INLINE vec4 csmWaveTexture(vec4 wave) {
  vec4 next = csmWaveRotate(wave);
  vec4 basis = vec4(wave[0], wave[1], next[0], next[1]) * 0.5f + vec4(0.5f);
  return clamp(basis, vec4(0.0f), vec4(1.0f));
}

// The wave of the texture after this one (two terms on).
PENUMBRA_INLINE vec4 csmWaveNextTexture(vec4 wave) {
  return csmWaveRotate(csmWaveRotate(wave));
}

// Basis texture `index` alone (terms 2 index + 1 and 2 index + 2), by the same rotations as the
// encode's walk over every texture, so both give the same values.
PENUMBRA_INLINE vec4 csmEncodeTexture(float depth, int index, CsmParams p) {
  vec4 wave = csmWaveStart(depth, p);
  for (int i = 0; i < index; ++i) wave = csmWaveNextTexture(wave);
  return csmWaveTexture(wave);
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
  // The receiver's terms by the encode's rotations: at d = z each product cancels as exactly as
  // the stored basis allows.
  vec4 wave = csmWave(d);
  float f = 0.5f;
  for (int k = 1; k <= p.termCount; ++k) {
    int texel = (k - 1) / 2;
    int component = 2 * ((k - 1) % 2);
    float sinZ = 2.0f * filteredBasis[texel][component] - 1.0f;
    float cosZ = 2.0f * filteredBasis[texel][component + 1] - 1.0f;
    float c = csmFrequency(k);
    f += csmAttenuationFactor(k, p) * (2.0f / c) * (sinZ * wave[1] - cosZ * wave[0]);
    wave = csmWaveRotate(wave);
  }
  return f;
}

// The series scaled and clamped to [0,1] (§3.2.2).
PENUMBRA_INLINE float csmVisibility(vec4 filteredBasis[8], float receiverDepth, CsmParams p) {
  return clamp(p.scale * csmSeries(filteredBasis, receiverDepth, p), 0.0f, 1.0f);
}

PENUMBRA_END_SHARED
#endif
