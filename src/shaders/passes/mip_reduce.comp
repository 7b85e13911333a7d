// One mip level down: each texel reduces the 2x2 block below it by its channel's reduction; with
// an odd source size the last texel also takes the leftover row/column (shared/mip_span.h).
// FORCE_REDUCTION overrides the technique's reduction (the Z-max pyramid uses kReduceMax).
#include "../lib/technique_block.glsl"
#include "../shared/channel_reduction.h"
#include "../shared/mip_span.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray source;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform int sourceLevel;
uniform ivec2 sourceSize;
uniform ivec2 targetSize;
uniform int layerCount;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= targetSize.x || p.y >= targetSize.y) return;
  ivec2 xs = mipSourceSpan(p.x, targetSize.x, sourceSize.x);
  ivec2 ys = mipSourceSpan(p.y, targetSize.y, sourceSize.y);
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
      ChannelAccumulator acc = startReduction(reduction, params.esm.exponent);
      for (int y = ys.x; y <= ys.y; ++y) {
        for (int x = xs.x; x <= xs.y; ++x) {
          acc = accumulateTap(acc, texelFetch(source, ivec3(x, y, layer), sourceLevel)[c], weight);
        }
      }
      result[c] = reductionResult(acc);
    }
    imageStore(target, ivec3(p, layer), result);
  }
}
