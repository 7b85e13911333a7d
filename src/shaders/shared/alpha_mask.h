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

PENUMBRA_END_SHARED
#endif
