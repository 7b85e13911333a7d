// One mip level down, one layer: each texel reduces the 2x2 block below it by its channel's
// reduction; with an odd source size the last texel also takes the leftover row/column
// (shared/mip_span.h). FORCE_REDUCTION overrides the technique's reduction (the Z-max pyramid
// uses kReduceMax). A fragment pass, not a compute pass: the rasteriser writes the level in the
// texture's own tiling, as the driver's mipmap generation does, where imageStore scatters
// (2x slower on llvmpipe, docs/results/passes-llvmpipe-2026-12-01.md).
#include "../lib/layer_reduction.glsl"
#include "../shared/mip_span.h"

#ifndef PACKED_UNORM8
#define PACKED_UNORM8 0
#endif
// The source level alone (a view of one level): level 0 here, and never the level being drawn.
// PACKED_UNORM8: RGBA8 channels viewed as R32UI, one word per texel, unpacked here (one gather
// per 2x2 block; bilinear filtering of unorm8 is fixed point and inexact).
#if PACKED_UNORM8
layout(binding = 0) uniform usampler2DArray source;
vec4 sourceTexel(ivec3 at) {
  return unpackUnorm4x8(texelFetch(source, at, 0).x);
}
#else
layout(binding = 0) uniform sampler2DArray source;
vec4 sourceTexel(ivec3 at) {
  return texelFetch(source, at, 0);
}
#endif

uniform ivec2 sourceSize;
uniform ivec2 targetSize;
uniform int layer;

#ifndef BILINEAR_MEAN
#define BILINEAR_MEAN 0
#endif
#ifndef GATHER_ONE_CHANNEL
#define GATHER_ONE_CHANNEL 0
#endif
// HALVING: the source level is exactly twice the target on both axes (an even size), so every
// texel reduces the plain 2x2 block at 2p, 2p + 1: no spans to work out per fragment.
#ifndef HALVING
#define HALVING 0
#endif

#ifndef GATHER_PER_CHANNEL
#define GATHER_PER_CHANNEL 0
#endif

layout(location = 0) out vec4 reduced;

// A plain 2x2 block's channel by its reduction: `mean` from the bilinear sample, else the
// gathered texels reduced in the loop's order ((x0, y0), (x1, y0), (x0, y1), (x1, y1) are the
// gather's w, z, x, y).
float reduceGathered(int reduction, vec4 block, float mean) {
  if (reduction == kReduceMean) return mean;
  ChannelAccumulator acc = startReduction(reduction, params.esm.exponent);
  acc = accumulateTap(acc, block.w, 0.25f);
  acc = accumulateTap(acc, block.z, 0.25f);
  acc = accumulateTap(acc, block.x, 0.25f);
  acc = accumulateTap(acc, block.y, 0.25f);
  return reductionResult(acc);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
#if HALVING
  ivec2 xs = ivec2(2 * p.x, 2 * p.x + 1);
  ivec2 ys = ivec2(2 * p.y, 2 * p.y + 1);
  const bool plainBlock = true;
  vec2 corner = gl_FragCoord.xy / vec2(targetSize);  // (2p + 1) / (2 targetSize)
#else
  ivec2 xs = mipSourceSpan(p.x, targetSize.x, sourceSize.x);
  ivec2 ys = mipSourceSpan(p.y, targetSize.y, sourceSize.y);
  bool plainBlock = xs.y - xs.x == 1 && ys.y - ys.x == 1;
  vec2 corner = vec2(xs.y, ys.y) / vec2(sourceSize);
#endif
#if BILINEAR_MEAN && !PACKED_UNORM8
  // Every channel a mean and a plain 2x2 block: one bilinear sample at the block's shared corner
  // weighs its four texels 1/4 each, one fetch instead of four.
  if (plainBlock) {
    reduced = textureLod(source, vec3(corner, float(layer)), 0.0f);
    return;
  }
#endif
#if PACKED_UNORM8 && ALL_MEAN
  // The block's four words in one gather, summed in the loop's order below: (x0, y0), (x1, y0),
  // (x0, y1), (x1, y1) are the gather's w, z, x, y.
  if (plainBlock) {
    uvec4 block = textureGather(source, vec3(corner, float(layer)), 0);
    vec4 sum = accumulateMeanTexel(vec4(0.0f), unpackUnorm4x8(block.w), 0.25f);
    sum = accumulateMeanTexel(sum, unpackUnorm4x8(block.z), 0.25f);
    sum = accumulateMeanTexel(sum, unpackUnorm4x8(block.x), 0.25f);
    reduced = accumulateMeanTexel(sum, unpackUnorm4x8(block.y), 0.25f);
    return;
  }
#endif
#if GATHER_PER_CHANNEL && defined(LAYER_REDUCTIONS) && !PACKED_UNORM8
  // One layer of mixed reductions known at compile time (the power CDF's min, max and mean):
  // the mean channels from one bilinear sample, each other channel from one gather of its four
  // texels; gathers of channels the sample serves are dead code.
  if (plainBlock) {
    vec3 at = vec3(corner, float(layer));
    vec4 mean = textureLod(source, at, 0.0f);
    reduced = vec4(reduceGathered(LAYER_REDUCTIONS[0], textureGather(source, at, 0), mean[0]),
                   reduceGathered(LAYER_REDUCTIONS[1], textureGather(source, at, 1), mean[1]),
                   reduceGathered(LAYER_REDUCTIONS[2], textureGather(source, at, 2), mean[2]),
                   reduceGathered(LAYER_REDUCTIONS[3], textureGather(source, at, 3), mean[3]));
    return;
  }
#endif
#if GATHER_ONE_CHANNEL && !PACKED_UNORM8
  // One channel, reduced by other than a mean (ESM's log-space mean, the Z-max pyramid's max):
  // one gather at the block's shared corner returns its four texels, reduced in the same order
  // as the loop below — (x0, y0), (x1, y0), (x0, y1), (x1, y1) are the gather's w, z, x, y.
  if (plainBlock) {
    vec4 block = textureGather(source, vec3(corner, float(layer)), 0);
    ChannelAccumulator acc = startReduction(layerChannelReduction(layer, 0), params.esm.exponent);
    acc = accumulateTap(acc, block.w, 0.25f);
    acc = accumulateTap(acc, block.z, 0.25f);
    acc = accumulateTap(acc, block.x, 0.25f);
    acc = accumulateTap(acc, block.y, 0.25f);
    reduced = vec4(reductionResult(acc), 0.0f, 0.0f, 0.0f);
    return;
  }
#endif
  float weight = 1.0f / float((xs.y - xs.x + 1) * (ys.y - ys.x + 1));
  // Each source texel is fetched once for all four channels.
#if ALL_MEAN
  vec4 sum = vec4(0.0f);
  for (int y = ys.x; y <= ys.y; ++y) {
    for (int x = xs.x; x <= xs.y; ++x) {
      sum = accumulateMeanTexel(sum, sourceTexel(ivec3(x, y, layer)), weight);
    }
  }
  reduced = sum;
#else
  ChannelAccumulator acc[4];
  for (int c = 0; c < 4; ++c) {
    acc[c] = startReduction(layerChannelReduction(layer, c), params.esm.exponent);
  }
  for (int y = ys.x; y <= ys.y; ++y) {
    for (int x = xs.x; x <= xs.y; ++x) {
      vec4 texel = sourceTexel(ivec3(x, y, layer));
      for (int c = 0; c < 4; ++c) acc[c] = accumulateTap(acc[c], texel[c], weight);
    }
  }
  reduced = vec4(reductionResult(acc[0]), reductionResult(acc[1]), reductionResult(acc[2]),
                 reductionResult(acc[3]));
#endif
}
