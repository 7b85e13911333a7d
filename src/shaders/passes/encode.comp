// Encode pass: light-space depth -> the technique's channels (shared TexelEncoding), written to
// its storage format, for every cascade (the dispatch's z) at once. Each depth is fetched once and
// its texel layers encoded in order (CSM's basis waves rotate from one layer to the next). With
// MSAA every sample is encoded, then the samples are reduced like filter taps (moments are
// averaged after encoding). Hard and PCF have no encode: their lookup reads the depth.
#include "../lib/technique_block.glsl"
#include "../shared/channel_reduction.h"

layout(local_size_x = 8, local_size_y = 8) in;
// After the group's size, which it reads.
#include "../lib/column_rows.glsl"
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray channelImage;
#if MSAA
layout(binding = 0) uniform sampler2DMSArray depthMap;
uniform int sampleCount;
#else
layout(binding = 0) uniform sampler2DArray depthMap;
#endif
uniform ivec2 size;
// Channel layers per cascade, fixed per variant: the layer loop unrolls, so the range table is
// read at constant offsets (an index llvmpipe cannot see is uniform gathers per lane: LVSM's
// encode took 2.9x a copy with the table indexed by the loop counter, 1.1x unrolled; 7.4x when
// every invocation worked the ranges out; docs/results/passes-llvmpipe-2026-12-01.md).
const int layerCount = LAYER_COUNT;

#if MSAA
vec4 encodeSamples(ivec3 p, int texelLayer) {
  int count = techniqueChannelCount(penumbraTechnique, penumbraParams);
  ChannelAccumulator acc[4];
  for (int c = 0; c < 4; ++c) {
    int channel = 4 * texelLayer + c;
    int reduction = channel < count ? channelReduction(penumbraTechnique, channel, penumbraParams)
                                    : kReduceMean;
    acc[c] = startReduction(reduction, penumbraParams.esm.exponent);
  }
  for (int s = 0; s < sampleCount; ++s) {
    TexelEncoding e = texelEncodingAt(penumbraTechnique, texelFetch(depthMap, p, s).x, texelLayer,
                                      penumbraParams);
    vec4 v = encodeCurrentTexelLayer(penumbraTechnique, e,
                                     penumbraRangeTable.texelLayer[texelLayer], penumbraParams);
    for (int c = 0; c < 4; ++c) acc[c] = accumulateTap(acc[c], v[c], 1.0f / float(sampleCount));
  }
  return vec4(reductionResult(acc[0]), reductionResult(acc[1]), reductionResult(acc[2]),
              reductionResult(acc[3]));
}
#endif

void main() {
  int x = int(gl_GlobalInvocationID.x);
  int cascade = int(gl_GlobalInvocationID.z);  // its depth layer
  if (x >= size.x || invocationRow(0) >= size.y) return;
  // Rows past the map's edge fetch its last row and store nowhere (invocationFetchRow).
  ivec3 texels[kRows];
  for (int k = 0; k < kRows; ++k) {
    texels[k] = ivec3(x, invocationRow(k), cascade);
  }
#if MSAA
  for (int k = 0; k < kRows; ++k) {
    ivec3 fetched = ivec3(x, invocationFetchRow(k, size.y), cascade);
    for (int layer = 0; layer < layerCount; ++layer) {
      imageStore(channelImage, ivec3(texels[k].xy, cascade * layerCount + layer),
                 encodeSamples(fetched, layer));
    }
  }
#else
  TexelEncoding encodings[kRows];
  for (int k = 0; k < kRows; ++k) {
    float depth = texelFetch(depthMap, ivec3(x, invocationFetchRow(k, size.y), cascade), 0).x;
    encodings[k] = startTexelEncoding(penumbraTechnique, depth, penumbraParams);
  }
  for (int layer = 0; layer < layerCount; ++layer) {
    vec4 ranges = penumbraRangeTable.texelLayer[layer];
    for (int k = 0; k < kRows; ++k) {
      imageStore(channelImage, ivec3(texels[k].xy, cascade * layerCount + layer),
                 encodeCurrentTexelLayer(penumbraTechnique, encodings[k], ranges, penumbraParams));
      encodings[k] = nextTexelLayer(penumbraTechnique, encodings[k]);
    }
  }
#endif
}
