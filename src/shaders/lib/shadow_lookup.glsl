// Shadow lookup for the camera pass: the technique's channels fetched by the chosen filter mode
// (point, hardware bilinear/trilinear/anisotropic, or a summed-area box sized from the pixel's
// footprint), then reconstructed by the shared dispatcher; PCF and the hard test run their
// kernel over the raw depth with constant, slope-scaled and receiver-plane bias.
#ifndef PENUMBRA_LIB_SHADOW_LOOKUP_GLSL
#define PENUMBRA_LIB_SHADOW_LOOKUP_GLSL
#include "technique_block.glsl"

const int kFilterPoint = 0;
const int kFilterBilinear = 1;
const int kFilterTrilinear = 2;
const int kFilterAnisotropic = 3;
const int kFilterSummedArea = 4;

layout(binding = 0) uniform sampler2DArray channelMap;
uniform int filterMode;
uniform int channelLayers;
uniform int shadowMapSize;
uniform int satMinRadius;  // the blur radius: the smallest summed-area box

#if SUMMED_AREA
#include "summed_area.glsl"
layout(std430, binding = 2) readonly buffer SatStats { SatChannelStats satStats[]; };
layout(std430, binding = 3) readonly buffer SatSums { uint64_t satSums[]; };

uint64_t satPrefix(int channel, int x, int y, ivec2 size) {
  if (x < 0 || y < 0) return 0UL;
  return satSums[satIndex(channel, x, y, size)];
}

float satBoxMean(int channel, ivec2 lo, ivec2 hi, ivec2 size) {
  uint64_t wrapped = satPrefix(channel, hi.x, hi.y, size) - satPrefix(channel, lo.x - 1, hi.y, size) -
                     satPrefix(channel, hi.x, lo.y - 1, size) +
                     satPrefix(channel, lo.x - 1, lo.y - 1, size);
  double area = double(hi.x - lo.x + 1) * double(hi.y - lo.y + 1);
  SatChannelStats s = satStats[channel];
  return float(double(int64_t(wrapped)) * s.step / area + s.centre);
}
#endif

// Fills the technique's filtered channels at uv. uvDx, uvDy are the screen derivatives of uv.
void fetchChannels(vec2 uv, vec2 uvDx, vec2 uvDy, inout float channels[kMaxChannels]) {
  int count = techniqueChannelCount(technique, params);
#if SUMMED_AREA
  ivec2 size = ivec2(shadowMapSize);
  vec2 footprint = max(abs(uvDx), abs(uvDy)) * float(shadowMapSize);
  int radius = max(satMinRadius, int(ceil(0.5f * max(footprint.x, footprint.y) - 0.5f)));
  ivec2 centre = clamp(ivec2(floor(uv * float(shadowMapSize))), ivec2(0), size - 1);
  ivec2 lo = clamp(centre - radius, ivec2(0), size - 1);
  ivec2 hi = clamp(centre + radius, ivec2(0), size - 1);
  for (int c = 0; c < count; ++c) channels[c] = satBoxMean(c, lo, hi, size);
#else
  for (int layer = 0; layer < channelLayers; ++layer) {
    vec4 v;
    if (filterMode == kFilterPoint) {
      ivec2 texel = clamp(ivec2(floor(uv * float(shadowMapSize))), ivec2(0), ivec2(shadowMapSize - 1));
      v = texelFetch(channelMap, ivec3(texel, layer), 0);
    } else {
      v = textureGrad(channelMap, vec3(uv, float(layer)), uvDx, uvDy);
    }
    for (int c = 0; c < 4; ++c) {
      if (4 * layer + c < count) channels[4 * layer + c] = v[c];
    }
  }
#endif
}

// PCF (or the hard test, a 1-tap PCF) over the raw depth in channel 0. depthPerTexel is the
// receiver plane's depth gradient per shadow-map texel (receiver-plane depth bias).
float pcfLookup(vec2 uv, float receiverDepth, vec2 depthPerTexel, PcfParams pcf) {
  vec2 position = uv * float(shadowMapSize);
  bool bilinear = pcf.kernel == kKernelBilinear;
  vec2 origin = bilinear ? floor(position - 0.5f) : floor(position);
  vec2 fraction = bilinear ? position - 0.5f - origin : vec2(0.0f);
  float slope = abs(depthPerTexel.x) + abs(depthPerTexel.y);
  float lit = 0.0f;
  for (int j = pcfFirstTap(pcf); j <= pcfLastTap(pcf); ++j) {
    for (int i = pcfFirstTap(pcf); i <= pcfLastTap(pcf); ++i) {
      float w = pcfTapWeight(i, j, fraction, pcf);
      if (w <= 0.0f) continue;
      vec2 tap = origin + vec2(i, j);
      float z = texelFetch(channelMap, ivec3(clamp(ivec2(tap), ivec2(0), ivec2(shadowMapSize - 1)), 0), 0).x;
      float d = receiverDepth;
      if (pcf.receiverPlane != 0) d += dot(depthPerTexel, tap + 0.5f - position);
      lit += w * hardVisibility(z, biasedReceiverDepth(d, slope, pcf.bias));
    }
  }
  return clamp(lit, 0.0f, 1.0f);  // the weights sum to 1 up to fp32 rounding
}

float shadowVisibility(vec2 uv, float receiverDepth, vec2 uvDx, vec2 uvDy, vec2 depthPerTexel) {
  if (technique == kTechniquePcf) return pcfLookup(uv, receiverDepth, depthPerTexel, params.pcf);
  if (technique == kTechniqueHard) {
    PcfParams single = params.pcf;
    single.kernel = kKernelBox;
    single.radius = 0;
    single.receiverPlane = 0;
    single.bias = params.hard;
    return pcfLookup(uv, receiverDepth, depthPerTexel, single);
  }
  float channels[kMaxChannels];
  for (int i = 0; i < kMaxChannels; ++i) channels[i] = 0.0f;
  fetchChannels(uv, uvDx, uvDy, channels);
  return reconstructVisibility(technique, channels, receiverDepth, params);
}

#endif
