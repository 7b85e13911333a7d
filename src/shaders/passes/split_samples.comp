// Lloyd relaxation samples for layered VSM (thesis §4.1.2): per 2x2 texel block, the shared
// secondOccluderSample (shared/layer_placement.h), as the CPU reference takes it.
#include "../shared/layer_placement.h"
layout(local_size_x = 8, local_size_y = 8) in;
#if MSAA
layout(binding = 0) uniform sampler2DMSArray depthMap;
#else
layout(binding = 0) uniform sampler2DArray depthMap;
#endif
layout(std430, binding = 1) writeonly buffer Samples {
  vec2 samples[];
};
uniform ivec2 size;

void main() {
  // z: the cascade; every cascade's samples feed one placement (one depth metric for all).
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (p.x + 1 >= size.x || p.y + 1 >= size.y) return;
  vec4 block = vec4(texelFetch(depthMap, p, 0).x, texelFetch(depthMap, p + ivec3(1, 0, 0), 0).x,
                    texelFetch(depthMap, p + ivec3(0, 1, 0), 0).x,
                    texelFetch(depthMap, p + ivec3(1, 1, 0), 0).x);
  SecondOccluderSample s = secondOccluderSample(block);
  samples[(p.z * (size.y - 1) + p.y) * (size.x - 1) + p.x] = vec2(s.depth, s.weight);
}
