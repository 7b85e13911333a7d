// One axis of the separable prefilter over one channel layer (box or Gaussian weights from
// shared/filter_weights.h, computed on the CPU and passed in): clamp-to-edge taps, each channel
// reduced by its technique's reduction. Accumulation is fp32 whatever the storage, so fp16
// storage cannot overflow.
// The taps are image loads of one layer bound as a 2D image: on llvmpipe a texel fetch through a
// sampler costs up to three of them, and a loop bounded by a uniform 1.4x one of constant trip
// count (docs/results/passes-llvmpipe-2026-12-04.md). So one map compiles its radius in (RADIUS:
// the user's kernel, one variant); cascades, whose kernels follow the view, take it as a uniform
// rather than compiling a variant for every radius the camera passes through.
// With the radius, its weights are compiled in (WEIGHTS, their exact bits): read from a uniform
// array, the exponential techniques' blur of one map took 1.12-1.36x the plain blur of constant
// weights on llvmpipe, 0.90-1.10x as constants (docs/results/passes-llvmpipe-2026-12-07.md).
// The accumulation is precise (shared/channel_reduction.h), so the compiler cannot regroup the
// constant weights' sum, w t0 + w t1 into w (t0 + t1): a box's unit-weight sum of exponentials
// would pass fp32's range, and MSM's ill-conditioned moments part from the CPU twin's. A box
// over other channels (TAPS_ALIKE) sums its taps and scales once, as the CPU twin does.
#include "../lib/layer_reduction.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1, CHANNEL_FORMAT) uniform readonly image2D source;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2D target;

#ifdef RADIUS
const int kRadius = RADIUS;
const float weights[2 * kRadius + 1] = WEIGHTS;
#define BLUR_RADIUS kRadius
#else
uniform int radius;
uniform float weights[2 * kMaxBlurRadius + 1];
#define BLUR_RADIUS radius
#endif
#include "../lib/blur_taps.glsl"
uniform ivec2 direction;
uniform ivec2 size;
uniform int layer;  // the channel layer within its cascade: its channels' reductions

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  // Each tap's texel is loaded once for all four channels.
#if ALL_MEAN
  vec4 sum = vec4(0.0f);
  for (int i = -BLUR_RADIUS; i <= BLUR_RADIUS; ++i) {
    ivec2 q = clamp(p + i * direction, ivec2(0), size - 1);
    sum = accumulateMeanTexel(sum, imageLoad(source, q), TAP_WEIGHT(i + BLUR_RADIUS));
  }
#if TAPS_ALIKE
  sum = scaleMeanTexel(sum, ALIKE_TAPS_WEIGHT);
#endif
  imageStore(target, p, sum);
#else
  ChannelAccumulator acc[4];
  for (int c = 0; c < 4; ++c) {
    acc[c] = startReduction(layerChannelReduction(layer, c), penumbraParams.esm.exponent);
  }
  for (int i = -BLUR_RADIUS; i <= BLUR_RADIUS; ++i) {
    ivec2 q = clamp(p + i * direction, ivec2(0), size - 1);
    vec4 texel = imageLoad(source, q);
    float weight = TAP_WEIGHT(i + BLUR_RADIUS);
    for (int c = 0; c < 4; ++c) acc[c] = accumulateTap(acc[c], texel[c], weight);
  }
#if TAPS_ALIKE
  for (int c = 0; c < 4; ++c) acc[c] = scaleTapWeights(acc[c], ALIKE_TAPS_WEIGHT);
#endif
  imageStore(target, p,
             vec4(reductionResult(acc[0]), reductionResult(acc[1]), reductionResult(acc[2]),
                  reductionResult(acc[3])));
#endif
}
