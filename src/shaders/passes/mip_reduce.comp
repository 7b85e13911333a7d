// One mip level down: each texel reduces the 2x2 block below it by its channel's reduction; with
// an odd source size the last texel also takes the leftover row/column (as filters.cpp does).
// FORCE_REDUCTION overrides the technique's reduction (the Z-max pyramid uses kReduceMax).
#include "../lib/channel_reduce.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray source;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform int sourceLevel;
uniform ivec2 sourceSize;
uniform ivec2 targetSize;
uniform int layerCount;

ivec2 sourceSpan(int i, int count, int sourceCount) {
  int first = min(2 * i, sourceCount - 1);
  int last = i == count - 1 ? sourceCount - 1 : 2 * i + 1;
  return ivec2(first, last);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= targetSize.x || p.y >= targetSize.y) return;
  ivec2 xs = sourceSpan(p.x, targetSize.x, sourceSize.x);
  ivec2 ys = sourceSpan(p.y, targetSize.y, sourceSize.y);
  float weight = 1.0f / float((xs.y - xs.x + 1) * (ys.y - ys.x + 1));
  int count = techniqueChannelCount(technique, params);
  for (int layer = 0; layer < layerCount; ++layer) {
    vec4 result = vec4(0.0f);
    for (int c = 0; c < 4; ++c) {
      int channel = 4 * layer + c;
      if (channel >= count) continue;
#ifdef FORCE_REDUCTION
      int reduction = FORCE_REDUCTION;
#else
      int reduction = channelReduction(technique, channel, params);
#endif
      float acc = reduceStart(reduction);
      bool first = true;
      for (int y = ys.x; y <= ys.y; ++y) {
        for (int x = xs.x; x <= xs.y; ++x) {
          float v = texelFetch(source, ivec3(x, y, layer), sourceLevel)[c];
          acc = reduceAdd(reduction, acc, first, v, weight);
          first = false;
        }
      }
      result[c] = acc;
    }
    imageStore(target, ivec3(p, layer), result);
  }
}
