// Summed-area table, step 4: prefix sums down each column (wrapping, by design).
#extension GL_ARB_gpu_shader_int64 : require
#include "../lib/summed_area.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 3) buffer Sums {
  uint64_t sums[];
};

uniform ivec2 size;
uniform int channelCount;

void main() {
  int x = int(gl_GlobalInvocationID.x);
  int channel = int(gl_GlobalInvocationID.y);
  if (x >= size.x || channel >= channelCount) return;
  uint64_t running = 0UL;
  for (int y = 0; y < size.y; ++y) {
    uint i = satIndex(channel, x, y, size);
    running += sums[i];
    sums[i] = running;
  }
}
