// One axis of the separable prefilter (box or Gaussian weights from shared/filter_weights.h,
// computed on the CPU and passed in): clamp-to-edge taps, each channel reduced by its technique's
// reduction. Accumulation is fp32 whatever the storage, so fp16 storage cannot overflow.
#include "../lib/layer_reduction.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray source;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform float weights[2 * kMaxBlurRadius + 1];
uniform int radius;
uniform ivec2 direction;
uniform ivec2 size;
uniform int layerCount;  // channel layers per cascade
uniform int layerBase;   // the cascade's first layer: each cascade has its own kernel

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  for (int layer = 0; layer < layerCount; ++layer) {
    // Each tap's texel is fetched once for all four channels.
#if ALL_MEAN
    vec4 sum = vec4(0.0f);
    for (int i = -radius; i <= radius; ++i) {
      ivec2 q = clamp(p + i * direction, ivec2(0), size - 1);
      sum = accumulateMeanTexel(sum, texelFetch(source, ivec3(q, layerBase + layer), 0),
                                weights[i + radius]);
    }
    imageStore(target, ivec3(p, layerBase + layer), sum);
#else
    ChannelAccumulator acc[4];
    for (int c = 0; c < 4; ++c) {
      acc[c] = startReduction(layerChannelReduction(layer, c), penumbraParams.esm.exponent);
    }
    for (int i = -radius; i <= radius; ++i) {
      ivec2 q = clamp(p + i * direction, ivec2(0), size - 1);
      vec4 texel = texelFetch(source, ivec3(q, layerBase + layer), 0);
      float weight = weights[i + radius];
      for (int c = 0; c < 4; ++c) acc[c] = accumulateTap(acc[c], texel[c], weight);
    }
    imageStore(target, ivec3(p, layerBase + layer),
               vec4(reductionResult(acc[0]), reductionResult(acc[1]), reductionResult(acc[2]),
                    reductionResult(acc[3])));
#endif
  }
}
