// The only glue between GLSL 4.50 and C++20 for the shared headers in this folder.
// Shared code uses the common subset: GLM mirrors GLSL's types and functions on the C++ side.
// Rules: include guards, `f` literals, no swizzles, no out/inout, structs built member by member
// (constructor syntax differs), every function marked PENUMBRA_INLINE. Texture access only
// through the functions lookup_access.h declares, which each side defines over its own textures.
// PENUMBRA_PRECISE marks arithmetic where GLSL compilers must not fuse or reorder operations, so
// the GPU rounds as the C++ reference does: ill-conditioned (MSM's Hankel solve), or a sum whose
// regrouping could overflow (the prefilter's taps, channel_reduction.h). GLSL 4.50 §4.7.1 does not
// carry precise into the functions a precise value calls (Mesa inlines them first, so on
// llvmpipe it does reach them): a function whose values must keep the CPU's bits on any GPU
// marks its own (sin_cos_pi.h, csm.h's walk, msm.h's quantisation; the other encodes add no
// rounded product: VSM's, LVSM's and MSM's powers, the power CDF's clamp, the exponentials of a
// product, EVSM's 2z - 1 whose doubling is exact). No fma(): GLSL lets it round once or twice
// (Mesa 22.3's llvmpipe rounds twice, measured; a fused multiply-add unit once), so no C++ twin
// could give every device's bits.
#ifndef PENUMBRA_SHARED_PRELUDE_H
#define PENUMBRA_SHARED_PRELUDE_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#define PENUMBRA_INLINE inline
#define PENUMBRA_PRECISE
#define PENUMBRA_BEGIN_SHARED   \
  namespace penumbra::shaders { \
  using namespace glm;
#define PENUMBRA_END_SHARED }
#else
#define PENUMBRA_INLINE
#define PENUMBRA_PRECISE precise
#define PENUMBRA_BEGIN_SHARED
#define PENUMBRA_END_SHARED
#endif

#endif
