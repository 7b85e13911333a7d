// Lloyd relaxation samples for layered VSM (thesis §4.1.2): per 2x2 texel block, the shared
// secondOccluderSample (shared/layer_placement.h), as the CPU reference takes it. One invocation
// per row of blocks keeps the row's weighted samples (weight > 0), in order, at the front of the
// row's slot, and their count: flat blocks weigh nothing in a Lloyd step (accumulateLloyd skips
// them), and on the built-in scenes they are 95-99.6% of the blocks, which every one of the
// relaxation's steps (16 by default) would otherwise read again.
#include "../shared/layer_placement.h"
layout(local_size_x = kLloydRowsPerGroup) in;  // one invocation per row, as the sums pass
#if MSAA
layout(binding = 0) uniform sampler2DMSArray depthMap;
#else
layout(binding = 0) uniform sampler2DArray depthMap;
#endif
layout(std430, binding = 1) writeonly buffer Samples {
  vec2 samples[];
};
layout(std430, binding = 3) writeonly buffer RowCounts {
  int rowCounts[];
};
uniform ivec2 size;
uniform int rowCount;  // rows of blocks, every cascade's in turn

void main() {
  // Every cascade's rows feed one placement (one depth metric for all).
  int row = int(gl_GlobalInvocationID.x);
  if (row >= rowCount) return;
  int rowLength = size.x - 1;
  ivec3 p = ivec3(0, row % (size.y - 1), row / (size.y - 1));
  int count = 0;
  for (p.x = 0; p.x < rowLength; ++p.x) {
    vec4 block = vec4(texelFetch(depthMap, p, 0).x, texelFetch(depthMap, p + ivec3(1, 0, 0), 0).x,
                      texelFetch(depthMap, p + ivec3(0, 1, 0), 0).x,
                      texelFetch(depthMap, p + ivec3(1, 1, 0), 0).x);
    SecondOccluderSample s = secondOccluderSample(block);
    if (s.weight > 0.0f) {
      samples[row * rowLength + count] = vec2(s.depth, s.weight);
      ++count;
    }
  }
  rowCounts[row] = count;
}
