// Summed-area table, step 3: quantise each texel and take prefix sums along its row.
#extension GL_ARB_gpu_shader_int64 : require
#include "../lib/summed_area.glsl"

layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2DArray channelMap;
layout(std430, binding = 2) readonly buffer Stats {
  SatChannelStats stats[];
};
layout(std430, binding = 3) writeonly buffer Sums {
  uint64_t sums[];
};

uniform ivec2 size;
uniform int channelCount;  // every cascade's channels
uniform int channelsPerCascade;
uniform int layersPerCascade;

void main() {
  int y = int(gl_GlobalInvocationID.x);
  int channel = int(gl_GlobalInvocationID.y);
  if (y >= size.y || channel >= channelCount) return;
  SatChannelStats s = stats[channel];
  uint64_t running = 0UL;
  for (int x = 0; x < size.x; ++x) {
    float v = satChannelValue(channelMap, channel, x, y, channelsPerCascade, layersPerCascade);
    running += uint64_t(int64_t(round((double(v) - s.centre) / s.step)));
    sums[satIndex(channel, x, y, size)] = running;
  }
}
