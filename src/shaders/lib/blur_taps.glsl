// The weight of a prefilter tap. A box's taps weigh alike (TAPS_ALIKE, blurTapsAlikeDefine in
// src/gl/shadow_map_filter.cpp): the passes add each at unit weight and scale the total once by
// the common weight, weights[0] (shared/channel_reduction.h scaleTapWeights), a multiply per
// texel instead of per tap; other kernels weigh each tap. Included after the pass declares its
// `weights` (constants compiled in, or a uniform array).
#ifndef PENUMBRA_LIB_BLUR_TAPS_GLSL
#define PENUMBRA_LIB_BLUR_TAPS_GLSL
#if TAPS_ALIKE
#define TAP_WEIGHT(i) 1.0f
#define ALIKE_TAPS_WEIGHT weights[0]
#else
#define TAP_WEIGHT(i) weights[i]
#endif
#endif
