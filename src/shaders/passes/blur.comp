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
    // Each tap's texel is fetched once for all four channels; a layer's unused components
    // (beyond the technique's channels) are blurred as means and never read.
    ChannelAccumulator acc[4];
    for (int c = 0; c < 4; ++c) {
      int channel = 4 * layer + c;
      int reduction = channel < count ? channelReduction(technique, channel, params) : kReduceMean;
      acc[c] = startReduction(reduction, params.esm.exponent);
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
  }
}
