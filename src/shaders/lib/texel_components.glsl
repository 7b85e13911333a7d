// A channel texel as the format stores it (TEXEL_COMPONENTS: 1, 2 or 4, fusedTileDefines):
// `Texel` (float, vec2 or vec4), `.TEXEL_SWIZZLE` narrowing a vec4 to it and widenTexel back,
// the components beyond the format 0. The fused prefilter and its minimal kernel keep their
// shared-memory tiles in it: llvmpipe reads and writes shared memory one lane and one component
// at a time, so RGBA32F arrays for an R32F map did four times the traffic.
#ifndef PENUMBRA_LIB_TEXEL_COMPONENTS_GLSL
#define PENUMBRA_LIB_TEXEL_COMPONENTS_GLSL

#if TEXEL_COMPONENTS == 1
#define Texel float
#define TEXEL_SWIZZLE x
#elif TEXEL_COMPONENTS == 2
#define Texel vec2
#define TEXEL_SWIZZLE xy
#else
#define Texel vec4
#define TEXEL_SWIZZLE xyzw
#endif

vec4 widenTexel(float t) { return vec4(t, 0.0f, 0.0f, 0.0f); }
vec4 widenTexel(vec2 t) { return vec4(t, 0.0f, 0.0f); }
vec4 widenTexel(vec4 t) { return t; }

#endif
