// One mip level down, one layer: each texel reduces the 2x2 block below it by its channel's
// reduction; with an odd source size the last texel also takes the leftover row/column
// (shared/mip_span.h). FORCE_REDUCTION overrides the technique's reduction (the Z-max pyramid
// uses kReduceMax). A fragment pass, not a compute pass: the rasteriser writes the level in the
// texture's own tiling, as the driver's mipmap generation does, where imageStore scatters
// (2x slower on llvmpipe, docs/results/passes-llvmpipe-2026-12-01.md).
//
// The source texels are read whole, each once for all four channels, by imageLoad: on llvmpipe
// four image loads of a 2x2 block cost about as much as the one bilinear sample of the driver's
// own mipmap generation, where four texelFetches cost 1.4x as much, and one bilinear sample for
// the means beside one gather per min or max channel as much again (the power CDF's mips at
// 4096^2: 0.92-1.01x the driver's against 1.43-1.68x, docs/results/passes-llvmpipe-2026-12-02.md).
// Every reduction, the mean included, is then the CPU's sum in the CPU's order (reduceMipLevel):
// no filtering hardware's rounding, no unorm8 fixed point.
#include "../lib/layer_reduction.glsl"
#include "../shared/mip_span.h"

// The source level alone, bound as an image in the texture's own format (MipChainPass): never
// the level being drawn.
layout(binding = 0, SOURCE_FORMAT) restrict readonly uniform image2DArray source;

uniform ivec2 sourceSize;
uniform ivec2 targetSize;
uniform int layer;

// HALVING: the source level is exactly twice the target on both axes (an even size), so every
// texel reduces the plain 2x2 block at 2p, 2p + 1: constant trip counts, and the loops unroll.
#ifndef HALVING
#define HALVING 0
#endif

layout(location = 0) out vec4 reduced;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
#if HALVING
  ivec2 origin = 2 * p;
  const ivec2 extent = ivec2(2, 2);
#else
  ivec2 xs = mipSourceSpan(p.x, targetSize.x, sourceSize.x);
  ivec2 ys = mipSourceSpan(p.y, targetSize.y, sourceSize.y);
  ivec2 origin = ivec2(xs.x, ys.x);
  ivec2 extent = ivec2(xs.y - xs.x + 1, ys.y - ys.x + 1);
#endif
  float weight = 1.0f / float(extent.x * extent.y);
#if ALL_MEAN
  vec4 sum = vec4(0.0f);
  for (int y = 0; y < extent.y; ++y) {
    for (int x = 0; x < extent.x; ++x) {
      sum = accumulateMeanTexel(sum, imageLoad(source, ivec3(origin + ivec2(x, y), layer)), weight);
    }
  }
  reduced = sum;
#else
  ChannelAccumulator acc[4];
  for (int c = 0; c < 4; ++c) {
    acc[c] = startReduction(layerChannelReduction(layer, c), penumbraParams.esm.exponent);
  }
  for (int y = 0; y < extent.y; ++y) {
    for (int x = 0; x < extent.x; ++x) {
      vec4 texel = imageLoad(source, ivec3(origin + ivec2(x, y), layer));
      for (int c = 0; c < 4; ++c) acc[c] = accumulateTap(acc[c], texel[c], weight);
    }
  }
  reduced = vec4(reductionResult(acc[0]), reductionResult(acc[1]), reductionResult(acc[2]),
                 reductionResult(acc[3]));
#endif
}
