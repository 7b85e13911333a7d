// One axis of the separable prefilter (box or Gaussian weights from shared/filter_weights.h,
// computed on the CPU and passed in): clamp-to-edge taps, each channel reduced by its technique's
// reduction. Accumulation is fp32 whatever the storage, so fp16 storage cannot overflow.
#include "../lib/technique_block.glsl"
#include "../shared/channel_reduction.h"

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
  int count = techniqueChannelCount(technique, params);
  for (int layer = 0; layer < layerCount; ++layer) {
    vec4 result = vec4(0.0f);
    for (int c = 0; c < 4; ++c) {
      int channel = 4 * layer + c;
      if (channel >= count) continue;
      ChannelAccumulator acc =
          startReduction(channelReduction(technique, channel, params), params.esm.exponent);
      for (int i = -radius; i <= radius; ++i) {
        ivec2 q = clamp(p + i * direction, ivec2(0), size - 1);
        acc = accumulateTap(acc, texelFetch(source, ivec3(q, layerBase + layer), 0)[c], weights[i + radius]);
      }
      result[c] = acc.value;
    }
    imageStore(target, ivec3(p, layerBase + layer), result);
  }
}
