// Moment shadow maps, four-moment Hamburger variant (Peters & Klein, I3D 2015; see
// docs/papers.md): store (z, z^2, z^3, z^4), filter linearly, and reconstruct the
// shadow intensity from a three-atom distribution consistent with the biased moments.
#ifndef PENUMBRA_SHARED_MSM_H
#define PENUMBRA_SHARED_MSM_H
#include "chebyshev.h"
#include "constants.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct MsmParams {
  float momentBias;      // alpha of the moment bias, [0, 0.01], or kMsmMomentBiasAuto (default):
                         // the storage's own, 3e-5 for 16-bit and 3e-6 for fp32 (msm notes)
  float depthBias;       // subtracted from the receiver depth, [0, 0.1]; 0.001 keeps planar
                         // receivers lit under 16-bit quantisation (msm_test)
  float bleedReduction;  // thesis §3.4 clamp applied to the visibility, [0, 0.99]
  int storage;           // kStorageUnorm16 (optimised quantisation) or kStorageFloat32
};

// momentBias below 0: the bias follows the storage format (msmMomentBias).
const float kMsmMomentBiasAuto = -1.0f;

PENUMBRA_INLINE MsmParams msmDefaultParams() {
  MsmParams p;
  p.momentBias = kMsmMomentBiasAuto;
  p.depthBias = 0.001f;
  p.bleedReduction = 0.0f;
  p.storage = kStorageUnorm16;
  return p;
}

// The notes' alpha for a storage format: 3e-5 for 16-bit, 3e-6 for 32-bit.
PENUMBRA_INLINE float msmDefaultMomentBias(int storage) {
  return storage == kStorageUnorm16 ? 0.00003f : 0.000003f;
}

// The moment bias in use: the given one, or the storage's default when it is left on auto.
PENUMBRA_INLINE float msmMomentBias(MsmParams p) {
  return p.momentBias < 0.0f ? msmDefaultMomentBias(p.storage) : p.momentBias;
}

// Offset added to the first quantised moment (Peters & Klein §4).
const float kMsmQuantizationOffset = 0.035955884801f;

// q = E b: each group of four literals is one published row of E, which becomes a column of
// the GLM/GLSL mat4, so that mat4 * b computes q_j = sum_i b_i E[i][j].
// clang-format off
PENUMBRA_INLINE mat4 msmQuantizationMatrix() {
  return mat4(-2.07224649f,    13.7948857237f,  0.105877704f,   9.7924062118f,
              32.23703778f,   -59.4683975703f, -1.9077466311f, -33.7652110555f,
              -68.571074599f,  82.0359750338f,  9.3496555107f,  47.9456096605f,
              39.3703274134f, -35.364903257f,  -6.6543490743f, -23.9728048165f);
}

// b_j = sum_i (q - offset)_i D[i][j], laid out like msmQuantizationMatrix.
PENUMBRA_INLINE mat4 msmDequantizationMatrix() {
  return mat4(0.2227744146f,  0.1549679261f,  0.1451988946f,  0.163127443f,
              0.0771972861f,  0.1394629426f,  0.2120202157f,  0.2591432266f,
              0.7926986636f,  0.7963415838f,  0.7258694464f,  0.6539092497f,
              0.0319417555f, -0.1722823173f, -0.2758014811f, -0.3376131734f);
}
// clang-format on

PENUMBRA_INLINE vec4 msmPowers(float depth) {
  float z2 = depth * depth;
  return vec4(depth, z2, z2 * depth, z2 * z2);
}

// Stored channels: the raw powers for fp32, the optimised quantisation for unorm16.
PENUMBRA_INLINE vec4 msmEncode(float depth, MsmParams p) {
  vec4 b = msmPowers(depth);
  if (p.storage != kStorageUnorm16) return b;
  // Precise, as the decode: the only encode of any technique with products to add, which a GPU
  // could otherwise fuse and round apart from the CPU's (prelude.h).
  PENUMBRA_PRECISE vec4 quantized =
      msmQuantizationMatrix() * b + vec4(kMsmQuantizationOffset, 0.0f, 0.0f, 0.0f);
  return quantized;
}

PENUMBRA_INLINE vec4 msmDecode(vec4 stored, MsmParams p) {
  if (p.storage != kStorageUnorm16) return stored;
  PENUMBRA_PRECISE vec4 b =
      msmDequantizationMatrix() * (stored - vec4(kMsmQuantizationOffset, 0.0f, 0.0f, 0.0f));
  return b;
}

const float kMsmFarRoot = 1.0e6f;

// a / b clamped to [-kMsmFarRoot, kMsmFarRoot], the sign kept when b is 0.
PENUMBRA_INLINE float msmSafeDivide(float a, float b) {
  PENUMBRA_PRECISE float limit = kMsmFarRoot * abs(b);
  if (abs(a) >= limit) return (a < 0.0f) != (b < 0.0f) ? -kMsmFarRoot : kMsmFarRoot;
  return a / b;
}

// Shadow intensity G in [0,1] (fraction occluded) from filtered power moments b, following the
// notes' steps 1-4: bias, Cholesky solve of the Hankel system, quadratic roots, three cases.
PENUMBRA_INLINE float msmShadowIntensity(vec4 b, float receiverDepth, float momentBias) {
  PENUMBRA_PRECISE vec4 bb = mix(b, vec4(0.5f), momentBias);
  PENUMBRA_PRECISE float zf = receiverDepth;
  // LDL^T of [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]]; the bias keeps d22, d33 > 0.
  PENUMBRA_PRECISE float d22 = max(bb.y - bb.x * bb.x, 1.0e-12f);
  PENUMBRA_PRECISE float l32 = (bb.z - bb.x * bb.y) / d22;
  PENUMBRA_PRECISE float d33 = max(bb.w - bb.y * bb.y - l32 * l32 * d22, 1.0e-12f);
  // Forward, diagonal and back substitution for c with rhs (1, zf, zf^2).
  PENUMBRA_PRECISE float w2 = zf - bb.x;
  PENUMBRA_PRECISE float w3 = zf * zf - bb.y - l32 * w2;
  PENUMBRA_PRECISE float c3 = w3 / d33;
  PENUMBRA_PRECISE float c2 = w2 / d22 - l32 * c3;
  PENUMBRA_PRECISE float c1 = 1.0f - bb.x * c2 - bb.y * c3;
  // Roots z2 <= z3 of c3 z^2 + c2 z + c1 = 0 in the cancellation-free form q / c3, c1 / q. When
  // the moments are (numerically) those of at most two atoms, c3 vanishes and one root runs off
  // to infinity; roots are clamped to +-kMsmFarRoot, which is infinity for depths in [0,1].
  PENUMBRA_PRECISE float discriminant = max(c2 * c2 - 4.0f * c1 * c3, 0.0f);
  PENUMBRA_PRECISE float q = -0.5f * (c2 + (c2 < 0.0f ? -1.0f : 1.0f) * sqrt(discriminant));
  PENUMBRA_PRECISE float rootA = msmSafeDivide(q, c3);
  PENUMBRA_PRECISE float rootB = msmSafeDivide(c1, q);
  PENUMBRA_PRECISE float z2 = min(rootA, rootB);
  PENUMBRA_PRECISE float z3 = max(rootA, rootB);
  if (zf <= z2) return 0.0f;
  if (zf <= z3) {
    float denominator = max((z3 - z2) * (zf - z2), 1.0e-30f);
    return clamp((zf * z3 - bb.x * (zf + z3) + bb.y) / denominator, 0.0f, 1.0f);
  }
  PENUMBRA_PRECISE float denominator = max((zf - z2) * (zf - z3), 1.0e-30f);
  return clamp(1.0f - (z2 * z3 - bb.x * (z2 + z3) + bb.y) / denominator, 0.0f, 1.0f);
}

PENUMBRA_INLINE float msmVisibility(vec4 filteredStored, float receiverDepth, MsmParams p) {
  PENUMBRA_PRECISE vec4 b = msmDecode(filteredStored, p);
  PENUMBRA_PRECISE float g = msmShadowIntensity(b, receiverDepth - p.depthBias, msmMomentBias(p));
  return reduceLightBleeding(1.0f - g, p.bleedReduction);
}

PENUMBRA_END_SHARED
#endif
