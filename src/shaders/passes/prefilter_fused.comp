// The whole prefilter of one cascade in one dispatch: encode and both axes of the separable blur
// over a shared-memory tile. Each work group loads its TILE^2 texels and a radius-wide border of
// depth once, encodes each into shared memory (encode fused into the first axis: the encoded
// channels never go through a texture), blurs the rows of the tile and its border into shared
// memory, then the columns, and writes only the result: one texture write per texel where the
// separate passes write three (encode, horizontal, vertical) and fetch 2 * taps + 1 texels.
// Same taps, order and fp32 accumulation as encode.comp + blur.comp; clamping the loads to the
// map clamps every tap as those do, so 32-bit float channels come out the same to the bit (the
// renderer takes this path only for them: 16- and 8-bit storage rounds the horizontal result
// in the scratch texture, which the CPU reference reproduces).
#include "../lib/layer_reduction.glsl"
#include "../lib/texel_components.glsl"

// The radius at compile time (RADIUS): the shared arrays have their size, the loops a constant
// trip count. One map compiles its weights in too (WEIGHTS), as blur.comp does; cascades take
// them as uniforms: a Gaussian's weights follow each cascade's sigma, which follows the view.
const int kRadius = RADIUS;
#ifdef WEIGHTS
const float weights[2 * kRadius + 1] = WEIGHTS;
#else
uniform float weights[2 * kRadius + 1];
#endif
const int kSpan = TILE + 2 * kRadius;
#include "../lib/blur_taps.glsl"

layout(local_size_x = TILE, local_size_y = TILE) in;
layout(binding = 0) uniform sampler2DArray depthMap;  // one layer per cascade
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray channels;

uniform ivec2 size;
uniform int cascade;
uniform int layerCount;  // channel layers per cascade

// Both hold the format's components only (lib/texel_components.glsl).
shared Texel encoded[kSpan * kSpan];  // the tile and its border, row by row
shared Texel rows[kSpan * TILE];      // the horizontal pass: the tile's columns, every row

// The kernel over the taps at first, first + stride, ... of `encoded` (fromEncoded) or `rows`.
// Components beyond TEXEL_COMPONENTS come out 0: the image format stores none of them.
Texel reduceTaps(int first, int stride, bool fromEncoded, int layer) {
#if ALL_MEAN
  Texel sum = Texel(0.0f);
  for (int i = 0; i <= 2 * kRadius; ++i) {
    Texel texel = fromEncoded ? encoded[first + i * stride] : rows[first + i * stride];
    sum = accumulateMeanTexel(sum, texel, TAP_WEIGHT(i));
  }
#if TAPS_ALIKE
  sum = scaleMeanTexel(sum, ALIKE_TAPS_WEIGHT);
#endif
  return sum;
#else
  ChannelAccumulator acc[TEXEL_COMPONENTS];
  for (int c = 0; c < TEXEL_COMPONENTS; ++c) {
    acc[c] = startReduction(layerChannelReduction(layer, c), penumbraParams.esm.exponent);
  }
  for (int i = 0; i <= 2 * kRadius; ++i) {
    vec4 texel = widenTexel(fromEncoded ? encoded[first + i * stride] : rows[first + i * stride]);
    for (int c = 0; c < TEXEL_COMPONENTS; ++c) {
      acc[c] = accumulateTap(acc[c], texel[c], TAP_WEIGHT(i));
    }
  }
  vec4 result = vec4(0.0f);
  for (int c = 0; c < TEXEL_COMPONENTS; ++c) {
#if TAPS_ALIKE
    acc[c] = scaleTapWeights(acc[c], ALIKE_TAPS_WEIGHT);
#endif
    result[c] = reductionResult(acc[c]);
  }
  return result.TEXEL_SWIZZLE;
#endif
}

void main() {
  int layer = int(gl_WorkGroupID.z);  // the channel layer within the cascade
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * TILE - kRadius;
  int local = int(gl_LocalInvocationIndex);
  for (int i = local; i < kSpan * kSpan; i += TILE * TILE) {
    ivec2 q = clamp(origin + ivec2(i % kSpan, i / kSpan), ivec2(0), size - 1);
    TexelEncoding e =
        texelEncodingAt(penumbraTechnique, texelFetch(depthMap, ivec3(q, cascade), 0).x, layer,
                        penumbraParams);
    encoded[i] = encodeCurrentTexelLayer(penumbraTechnique, e, penumbraRangeTable.texelLayer[layer],
                                         penumbraParams)
                     .TEXEL_SWIZZLE;
  }
  barrier();
  for (int i = local; i < kSpan * TILE; i += TILE * TILE) {
    int x = i % TILE, y = i / TILE;
    rows[i] = reduceTaps(y * kSpan + x, 1, true, layer);
  }
  barrier();
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  ivec2 l = ivec2(gl_LocalInvocationID.xy);
  imageStore(channels, ivec3(p, cascade * layerCount + layer),
             widenTexel(reduceTaps(l.y * TILE + l.x, TILE, false, layer)));
}
