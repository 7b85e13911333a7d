// One mip level down: each texel reduces the 2x2 block below it by its channel's reduction; with
// an odd source size the last texel also takes the leftover row/column (shared/mip_span.h).
// FORCE_REDUCTION overrides the technique's reduction (the Z-max pyramid uses kReduceMax).
#include "../lib/layer_reduction.glsl"
#include "../shared/mip_span.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray source;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform int sourceLevel;
uniform ivec2 sourceSize;
uniform ivec2 targetSize;
uniform int layerCount;

#ifndef BILINEAR_MEAN
#define BILINEAR_MEAN 0
#endif

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= targetSize.x || p.y >= targetSize.y) return;
  ivec2 xs = mipSourceSpan(p.x, targetSize.x, sourceSize.x);
  ivec2 ys = mipSourceSpan(p.y, targetSize.y, sourceSize.y);
#if BILINEAR_MEAN
  // Every channel a mean and a plain 2x2 block: one bilinear sample at the block's shared corner
  // weighs its four texels 1/4 each (the sampler bound with this pass reads level sourceLevel
  // only), one fetch instead of four — what the driver's own mipmap generation does.
  if (xs.y - xs.x == 1 && ys.y - ys.x == 1) {
    vec2 corner = vec2(xs.y, ys.y) / vec2(sourceSize);
    for (int layer = 0; layer < layerCount; ++layer) {
      imageStore(target, ivec3(p, layer),
                 textureLod(source, vec3(corner, float(layer)), float(sourceLevel)));
    }
    return;
  }
#endif
  float weight = 1.0f / float((xs.y - xs.x + 1) * (ys.y - ys.x + 1));
  for (int layer = 0; layer < layerCount; ++layer) {
    // Each source texel is fetched once for all four channels.
#if ALL_MEAN
    vec4 sum = vec4(0.0f);
    for (int y = ys.x; y <= ys.y; ++y) {
      for (int x = xs.x; x <= xs.y; ++x) {
        sum = accumulateMeanTexel(sum, texelFetch(source, ivec3(x, y, layer), sourceLevel),
                                  weight);
      }
    }
    imageStore(target, ivec3(p, layer), sum);
#else
    ChannelAccumulator acc[4];
    for (int c = 0; c < 4; ++c) {
      acc[c] = startReduction(layerChannelReduction(layer, c), params.esm.exponent);
    }
    for (int y = ys.x; y <= ys.y; ++y) {
      for (int x = xs.x; x <= xs.y; ++x) {
        vec4 texel = texelFetch(source, ivec3(x, y, layer), sourceLevel);
        for (int c = 0; c < 4; ++c) acc[c] = accumulateTap(acc[c], texel[c], weight);
      }
    }
    imageStore(target, ivec3(p, layer),
               vec4(reductionResult(acc[0]), reductionResult(acc[1]), reductionResult(acc[2]),
                    reductionResult(acc[3])));
#endif
  }
}
