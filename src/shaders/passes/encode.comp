// Encode pass: light-space depth -> the technique's channels (shared encodeChannel), written to
// its storage format, for every cascade (the dispatch's z) at once. With MSAA every sample is encoded, then the samples are reduced like
// filter taps (moments are averaged after encoding); hard and PCF keep the nearest sample.
#include "../lib/technique_block.glsl"
#include "../shared/channel_reduction.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray channelImage;
#if MSAA
layout(binding = 0) uniform sampler2DMSArray depthMap;
uniform int sampleCount;
#else
layout(binding = 0) uniform sampler2DArray depthMap;
#endif
uniform ivec2 size;
uniform int layerCount;  // channel layers per cascade

float encodeTexel(ivec3 p, int channel) {
#if MSAA
  bool depthOnly = technique == kTechniqueHard || technique == kTechniquePcf;
  int reduction = depthOnly ? kReduceMin : channelReduction(technique, channel, params);
  ChannelAccumulator acc = startReduction(reduction, params.esm.exponent);
  for (int s = 0; s < sampleCount; ++s) {
    float v = encodeChannel(technique, texelFetch(depthMap, p, s).x, channel, params);
    acc = accumulateTap(acc, v, 1.0f / float(sampleCount));
  }
  return reductionResult(acc);
#else
  return encodeChannel(technique, texelFetch(depthMap, p, 0).x, channel, params);
#endif
}

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);  // z: the cascade, its depth layer
  if (p.x >= size.x || p.y >= size.y) return;
  int count = techniqueChannelCount(technique, params);
  for (int layer = 0; layer < layerCount; ++layer) {
    vec4 v = vec4(0.0f);
    for (int c = 0; c < 4; ++c) {
      int channel = 4 * layer + c;
      if (channel < count) v[c] = encodeTexel(p, channel);
    }
    imageStore(channelImage, ivec3(p.xy, p.z * layerCount + layer), v);
  }
}
