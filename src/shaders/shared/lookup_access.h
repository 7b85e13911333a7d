// The only part of the camera-pass lookup that differs between GPU and CPU: reading the shadow
// map's textures. shadow_lookup.h and filtered_reference.h call these; the GPU defines them over
// its samplers (lib/lookup_access.glsl), the CPU twin over the CPU reference filters' images
// (src/core/shadow_lookup.cpp). Texel coordinates are GL's: row 0 at the bottom.
#ifndef PENUMBRA_SHARED_LOOKUP_ACCESS_H
#define PENUMBRA_SHARED_LOOKUP_ACCESS_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// Names the textures of one lookup. The GPU's samplers are globals holding every cascade, so its
// handle is the cascade; a CPU twin holds one cascade's images.
#ifdef __cplusplus
struct CpuLookupTextures;
struct LookupSources {
  const CpuLookupTextures* textures;
};
#else
struct LookupSources {
  int cascade;
};
#endif

// Four channels (one layer of the channel texture) of a texel at a mip level.
vec4 channelTexel(LookupSources s, int layer, ivec2 texel, int level);
// Four channels filtered linearly at uv: bilinear within a level and linear between the two
// levels around `lod` (GL's textureLod with LINEAR_MIPMAP_LINEAR).
vec4 channelLinear(LookupSources s, int layer, vec2 uv, float lod);
// Four channels through the anisotropic filter for the footprint (uvDx, uvDy). The GPU asks the
// hardware (textureGrad); the CPU models it with lookupProbes (lookup_footprint.h).
vec4 channelAnisotropic(LookupSources s, int layer, vec2 uv, vec2 uvDx, vec2 uvDy);
// The light pass's linear depth at a level-0 texel, unfiltered (the nearest sample under MSAA).
float lightDepthTexel(LookupSources s, ivec2 texel);
// The same at the four texels texel + (0,0), (1,0), (0,1), (1,1) (x, y, z, w), each clamped into
// the map of `size` texels as clampTexel does: one gather on the GPU, where four fetches cost
// llvmpipe most of ESM's PCF fallback.
vec4 lightDepthQuad(LookupSources s, ivec2 texel, int size);
// ESM's Z-max pyramid: the largest depth under a texel of `level`.
float zmaxTexel(LookupSources s, ivec2 texel, int level);
// The prefilter's blur weights w_-r..w_r summed up to tap u, for u in [-r, r].
float blurCumulativeWeight(LookupSources s, int u);

// Summed-area access exists in C++ always and in GLSL in the SUMMED_AREA variant (64-bit integers).
#ifdef __cplusplus
#define PENUMBRA_SUMMED_AREA 1
#elif defined(SUMMED_AREA)
#define PENUMBRA_SUMMED_AREA SUMMED_AREA
#else
#define PENUMBRA_SUMMED_AREA 0
#endif

// The soft-shadow paths (soft_shadow.h: the blocker search and the penumbra's filter) exist in
// C++ always and in GLSL unless a shader that only ever passes a light of size 0 leaves them out
// by defining this 0 first: camera.frag's hard-light variants, penumbra_shadow.glsl. Folded away
// after inlining, the paths still cost the GLSL compiler (docs/renderer.md, the camera pass's
// variants).
#ifndef PENUMBRA_SOFT_SHADOWS
#define PENUMBRA_SOFT_SHADOWS 1
#endif

#if PENUMBRA_SUMMED_AREA
// A summed-area table (penumbra/summed_area_table.h): a channel's wrapping fixed-point prefix sum
// over [0,x] x [0,y] (0 when x or y < 0), and its centre and step.
uint64_t summedAreaPrefix(LookupSources s, int channel, int x, int y);
double summedAreaCentre(LookupSources s, int channel);
double summedAreaStep(LookupSources s, int channel);
#endif

PENUMBRA_END_SHARED
#endif
