// Exponential variance shadow maps (thesis §4.2): Chebyshev on positive and negative exponential
// warps of depth, the minimum of the two bounds. Exponents are clamped to what storage holds.
#ifndef PENUMBRA_SHARED_EVSM_H
#define PENUMBRA_SHARED_EVSM_H
#include "chebyshev.h"
#include "constants.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// Depth is mapped to [-1,1] before warping, so the second moment exp(2c) must fit the format:
// c <= ln(FLT_MAX)/2 = 44.36 for fp32 and ln(65504)/2 = 5.545 for fp16 (kept a little below).
const float kEvsmMaxExponentFloat32 = 42.0f;
const float kEvsmMaxExponentFloat16 = 5.54f;

struct EvsmParams {
  float positiveExponent;  // c+, [0.5, 42]; clamped further for fp16 storage
  float negativeExponent;  // c-, [0.5, 42]; EVSM4 only
  float minVariance;       // variance floor in linear depth^2 units, scaled by the warp's slope
  float bleedReduction;    // thesis §3.4 clamp, [0, 0.99]
  int storage;             // kStorageFloat32 or kStorageFloat16
  int pad0;
  int pad1;
  int pad2;
};

PENUMBRA_INLINE EvsmParams evsmDefaultParams() {
  EvsmParams p;
  p.positiveExponent = 40.0f;
  p.negativeExponent = 5.0f;
  p.minVariance = 0.00001f;
  p.bleedReduction = 0.0f;
  p.storage = kStorageFloat32;
  p.pad0 = 0;
  p.pad1 = 0;
  p.pad2 = 0;
  return p;
}

PENUMBRA_INLINE float evsmClampExponent(float exponent, int storage) {
  float limit = storage == kStorageFloat16 ? kEvsmMaxExponentFloat16 : kEvsmMaxExponentFloat32;
  return min(exponent, limit);
}

// (exp(c+ x), -exp(-c- x)) with x = 2*depth - 1: both increasing in depth.
PENUMBRA_INLINE vec2 evsmWarp(float depth, EvsmParams p) {
  float x = 2.0f * depth - 1.0f;
  float cPos = evsmClampExponent(p.positiveExponent, p.storage);
  float cNeg = evsmClampExponent(p.negativeExponent, p.storage);
  return vec2(exp(cPos * x), -exp(-cNeg * x));
}

// (pos, pos^2, neg, neg^2); EVSM2 keeps the first two channels.
PENUMBRA_INLINE vec4 evsmEncode(float depth, EvsmParams p) {
  vec2 w = evsmWarp(depth, p);
  return vec4(w.x, w.x * w.x, w.y, w.y * w.y);
}

// The variance floor is given in linear depth; the warp stretches depth by its slope
// |dw/dz| = 2c|w|, taken at the occluders' warped mean: a floor scaled at the receiver would put
// a constant lower bound (2c sigma)^2 / (1 + (2c sigma)^2) on the visibility of every far receiver.
PENUMBRA_INLINE float evsmWarpedMinVariance(float warpedMean, float exponent, EvsmParams p) {
  float slope = 2.0f * exponent * abs(warpedMean);
  return p.minVariance * slope * slope;
}

PENUMBRA_INLINE float evsmPositiveVisibility(vec2 moments, float receiverDepth, EvsmParams p) {
  float c = evsmClampExponent(p.positiveExponent, p.storage);
  float floorVariance = evsmWarpedMinVariance(moments.x, c, p);
  return chebyshevUpperBound(moments, evsmWarp(receiverDepth, p).x, floorVariance);
}

PENUMBRA_INLINE float evsmNegativeVisibility(vec2 moments, float receiverDepth, EvsmParams p) {
  float c = evsmClampExponent(p.negativeExponent, p.storage);
  float floorVariance = evsmWarpedMinVariance(moments.x, c, p);
  return chebyshevUpperBound(moments, evsmWarp(receiverDepth, p).y, floorVariance);
}

PENUMBRA_INLINE float evsm2Visibility(vec2 moments, float receiverDepth, EvsmParams p) {
  return reduceLightBleeding(evsmPositiveVisibility(moments, receiverDepth, p), p.bleedReduction);
}

PENUMBRA_INLINE float evsm4Visibility(vec4 moments, float receiverDepth, EvsmParams p) {
  float positive = evsmPositiveVisibility(vec2(moments.x, moments.y), receiverDepth, p);
  float negative = evsmNegativeVisibility(vec2(moments.z, moments.w), receiverDepth, p);
  return reduceLightBleeding(min(positive, negative), p.bleedReduction);
}

PENUMBRA_END_SHARED
#endif
