// `penumbra bench --passes`: the minimal kernel beside the summed-area table — the same reads of
// every channel and the same 64-bit writes, as plain prefix sums: AXIS 0 quantises each texel
// with one fixed scale and sums along its row; AXIS 1 sums the rows' results down each column.
// No per-channel statistics, no centring: what any 64-bit summed-area table has to do.
#extension GL_ARB_gpu_shader_int64 : require
#include "../lib/summed_area.glsl"

layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2DArray penumbraChannelMap;
layout(std430, binding = 3) buffer Sums {
  uint64_t sums[];
};

uniform ivec2 size;
uniform int channelCount;
uniform int layersPerCascade;

void main() {
  int line = int(gl_GlobalInvocationID.x);  // the row (AXIS 0) or column (AXIS 1)
  int channel = int(gl_GlobalInvocationID.y);
  if (line >= size.x || channel >= channelCount) return;
  uint64_t running = 0UL;
  for (int i = 0; i < size.x; ++i) {
#if AXIS == 0
    float v = satChannelValue(penumbraChannelMap, channel, i, line, channelCount, layersPerCascade);
    running += uint64_t(int64_t(v * 2147483648.0f));
    sums[satIndex(channel, i, line, size)] = running;
#else
    uint index = satIndex(channel, line, i, size);
    running += sums[index];
    sums[index] = running;
#endif
  }
}
