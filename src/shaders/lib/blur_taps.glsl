// The weight of a prefilter tap. A box's taps weigh alike (TAPS_ALIKE 1 or 2,
// blurTapsAlikeDefine in src/gl/shadow_map_filter.cpp). Where the channels allow it (1) the
// passes add each tap at unit weight and scale the total once by the common weight, weights[0]
// (shared/channel_reduction.h scaleTapWeights), a multiply per texel instead of per tap. Channels
// of exponentials (2) weigh each tap, their sum at unit weight could pass fp32's largest value,
// but by the one common weight: the same products as weights[i], and llvmpipe pays for every
// uniform element an invocation reads: ESM's 9-tap box prefilter at 2048² took 48.3-49.6 ms
// reading weights[i] and 42.9 reading weights[0], against 38.4-42.3 for the minimal blur
// (docs/results/passes-llvmpipe-2026-12-06-rows.md). Gaussians (0) weigh each tap by its own
// weight. Included after the pass declares its `weights` uniform.
#ifndef PENUMBRA_LIB_BLUR_TAPS_GLSL
#define PENUMBRA_LIB_BLUR_TAPS_GLSL
#if TAPS_ALIKE == 1
#define TAP_WEIGHT(i) 1.0f
#define ALIKE_TAPS_WEIGHT weights[0]
#elif TAPS_ALIKE == 2
#define TAP_WEIGHT(i) weights[0]
#else
#define TAP_WEIGHT(i) weights[i]
#endif
#endif
