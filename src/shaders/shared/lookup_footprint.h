// Where a camera-pass lookup reads the shadow map: the filter modes' taps, probes and levels
// from the pixel's screen derivatives, and the summed-area box. The GPU lookup, the CPU twin
// (penumbra/shadow_lookup.h) and the filtered reference all take their geometry from here.
#ifndef PENUMBRA_SHARED_LOOKUP_FOOTPRINT_H
#define PENUMBRA_SHARED_LOOKUP_FOOTPRINT_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// Filter modes, in the order of penumbra::gl::FilterMode.
const int kFilterPoint = 0;
const int kFilterBilinear = 1;
const int kFilterTrilinear = 2;
// Anisotropic: every channel through the probes the filtered reference models (lookupProbes);
// AnisotropicDriver: mean channels through the driver's own anisotropic filter, whose kernel is
// its own, so techniques pay different kernel-mismatch penalties (docs/techniques.md).
const int kFilterAnisotropic = 3;
const int kFilterSummedArea = 4;
const int kFilterAnisotropicDriver = 5;

// Everything the lookup needs to know about the shadow map and its prefilter.
struct LookupSettings {
  int filterMode;     // kFilter*
  int shadowMapSize;  // level-0 texels per side
  int channelLevels;  // mip levels of the channel texture (1 without mips)
  int anisotropy;     // most probes of the anisotropic mode, [1, 16]
  int blurKernel;     // kKernelBox or kKernelGaussian (filter_weights.h)
  int blurRadius;     // taps each side; also the smallest summed-area box
  float blurSigma;    // Gaussian standard deviation in texels
  int zmaxLevels;     // levels of ESM's Z-max pyramid (0 without it)
  // Cascade 0's texel over this cascade's (1: one map or cascade 0): PCF's kernel keeps its
  // world width across cascades like the prefilter's (cascade_selection.h).
  float kernelScale;
};

// Clamp-to-edge addressing.
PENUMBRA_INLINE ivec2 clampTexel(ivec2 texel, int size) {
  return clamp(texel, ivec2(0), ivec2(size - 1));
}

// The texel a point lookup (GL_NEAREST) reads.
PENUMBRA_INLINE ivec2 nearestTexel(vec2 uv, int size) {
  return clampTexel(ivec2(floor(uv * float(size))), size);
}

// A bilinear lookup as GL defines it: texels base + (0..1, 0..1), weights from `fraction`.
struct BilinearTaps {
  ivec2 base;
  vec2 fraction;
};

PENUMBRA_INLINE BilinearTaps bilinearTaps(vec2 uv, int size) {
  vec2 position = uv * float(size) - 0.5f;
  BilinearTaps t;
  t.base = ivec2(floor(position));
  t.fraction = position - vec2(t.base);
  return t;
}

PENUMBRA_INLINE float bilinearTapWeight(BilinearTaps t, int i, int j) {
  float wx = i == 0 ? 1.0f - t.fraction.x : t.fraction.x;
  float wy = j == 0 ? 1.0f - t.fraction.y : t.fraction.y;
  return wx * wy;
}

// Mip-mapped lookups as probes along the footprint's major axis (EXT_texture_filter_anisotropic:
// N = min(ceil(major/minor), anisotropy) probes at lod log2(major/N)); trilinear is one probe at
// log2(major). `axis` is the major axis in uv; the probes sit at its N equal sub-segment centres.
struct LookupProbes {
  int count;
  float lod;
  vec2 axis;
};

PENUMBRA_INLINE LookupProbes lookupProbes(vec2 uvDx, vec2 uvDy, LookupSettings s) {
  float lengthX = length(uvDx * float(s.shadowMapSize));
  float lengthY = length(uvDy * float(s.shadowMapSize));
  float major = max(max(lengthX, lengthY), 1.0e-6f);
  float minor = max(min(lengthX, lengthY), 1.0e-6f);
  LookupProbes p;
  p.count = 1;
  if (s.filterMode == kFilterAnisotropic || s.filterMode == kFilterAnisotropicDriver) {
    // Clamped as a float first: major / minor may exceed any int where a derivative vanishes.
    p.count = int(clamp(ceil(major / minor), 1.0f, float(max(s.anisotropy, 1))));
  }
  p.lod = log2(major / float(p.count));
  p.axis = lengthX >= lengthY ? uvDx : uvDy;
  return p;
}

PENUMBRA_INLINE vec2 probeOffset(LookupProbes p, int k) {
  return p.axis * ((float(k) + 0.5f) / float(p.count) - 0.5f);
}

// The two levels a trilinear probe blends and the upper one's weight.
struct TrilinearLevels {
  int level;
  int next;
  float fraction;
};

PENUMBRA_INLINE TrilinearLevels trilinearLevels(float lod, int levels) {
  float clamped = clamp(lod, 0.0f, float(levels - 1));
  TrilinearLevels t;
  t.level = int(floor(clamped));
  t.next = min(t.level + 1, levels - 1);
  t.fraction = clamped - float(t.level);
  return t;
}

// The summed-area lookup's box in continuous level-0 texel coordinates, clamped to the map:
// centred on the lookup, half-width max(blur radius + 1/2, half the footprint's larger side), so
// that it is at least the blur's 2r+1 texels and moves and grows smoothly (sub-texel corners).
struct SummedAreaBox {
  vec2 lo;
  vec2 hi;
};

PENUMBRA_INLINE SummedAreaBox summedAreaBox(vec2 uv, vec2 uvDx, vec2 uvDy, LookupSettings s) {
  float size = float(s.shadowMapSize);
  vec2 footprint = max(abs(uvDx), abs(uvDy)) * size;
  float halfWidth = max(float(s.blurRadius) + 0.5f, 0.5f * max(footprint.x, footprint.y));
  vec2 centre = uv * size;
  SummedAreaBox b;
  b.lo = clamp(centre - vec2(halfWidth), vec2(0.0f), vec2(size));
  b.hi = clamp(centre + vec2(halfWidth), vec2(0.0f), vec2(size));
  return b;
}

// The share of texel `texel` (one axis) that the interval [lo, hi] covers.
PENUMBRA_INLINE float intervalCoverage(int texel, float lo, float hi) {
  return clamp(min(float(texel + 1), hi) - max(float(texel), lo), 0.0f, 1.0f);
}

PENUMBRA_END_SHARED
#endif
