// Alpha-masked materials: the coverage test of the light and camera passes (glTF 2.0 §3.9.4,
// alphaMode MASK), and the texture unit their base-colour texture is bound to.
#ifndef PENUMBRA_SHARED_ALPHA_MASK_H
#define PENUMBRA_SHARED_ALPHA_MASK_H
#include "prelude.h"

// Units 0-3 hold the shadow lookup's textures (lib/lookup_access.glsl).
#define PENUMBRA_BASE_COLOR_TEXTURE_UNIT 4

PENUMBRA_BEGIN_SHARED

// alpha: base-colour texture alpha x factor alpha, in [0,1]; cutoff < 0 marks an opaque material.
PENUMBRA_INLINE bool alphaCovers(float alpha, float cutoff) {
  return cutoff < 0.0f || alpha >= cutoff;
}

// A translucent (BLEND) caster in the light pass lets through 1 - alpha of the light: it covers
// a shadow-map texel where alpha exceeds the texel's threshold of a 4x4 ordered (Bayer) dither,
// so every aligned 4x4 block holds round(16 alpha) covered texels and a filter of 4 texels or
// more averages the depth test to 1 - alpha (docs/techniques.md, "Translucent casters"). The
// ray-traced truth attenuates by exactly 1 - alpha. texel: the shadow-map texel's integer
// coordinates (gl_FragCoord.xy).
PENUMBRA_INLINE float translucencyThreshold(int x, int y) {
  const int row = y & 3;
  const int mixed = (x ^ y) & 3;
  // The Bayer matrix's index: bit-reversed interleave of (x xor y) and y.
  const int index = ((mixed & 1) << 3) | ((row & 1) << 2) | (mixed & 2) | ((row & 2) >> 1);
  return (float(index) + 0.5f) / 16.0f;
}

PENUMBRA_INLINE bool translucentCovers(float alpha, int x, int y) {
  return alpha > translucencyThreshold(x, y);
}

PENUMBRA_END_SHARED
#endif
