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
uniform int channelLevels;
uniform int anisotropy;
uniform int blurRadius;

// ESM in log space (Salvi) stores depth, and a hardware filter would average it linearly, which
// is not the log-space mean of exp(c z). These filter by hand in log space instead: bilinear
// within a level, linear between levels, and up to `anisotropy` probes along the footprint's
// major axis, as the hardware modes do.
float esmLogAccumulate(float acc, bool first, float value, float weight) {
  if (weight <= 0.0f) return acc;
  float term = esmLogSpaceWeighted(value, weight, params.esm.exponent);
  return first ? term : esmLogSpaceAdd(acc, term, params.esm.exponent);
}

float esmLogBilinear(vec2 uv, int level) {
  int size = max(shadowMapSize >> level, 1);
  vec2 position = uv * float(size) - 0.5f;
  ivec2 base = ivec2(floor(position));
  vec2 f = position - vec2(base);
  float acc = 0.0f;
  bool first = true;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      float w = (i == 0 ? 1.0f - f.x : f.x) * (j == 0 ? 1.0f - f.y : f.y);
      if (w <= 0.0f) continue;
      ivec2 texel = clamp(base + ivec2(i, j), ivec2(0), ivec2(size - 1));
      acc = esmLogAccumulate(acc, first, texelFetch(channelMap, ivec3(texel, 0), level).x, w);
      first = false;
    }
  }
  return acc;
}

float esmLogTrilinear(vec2 uv, float lod) {
  lod = clamp(lod, 0.0f, float(channelLevels - 1));
  int level = int(floor(lod));
  float t = lod - float(level);
  float acc = esmLogAccumulate(0.0f, true, esmLogBilinear(uv, level), 1.0f - t);
  if (t > 0.0f) acc = esmLogAccumulate(acc, t >= 1.0f, esmLogBilinear(uv, min(level + 1, channelLevels - 1)), t);
  return acc;
}

float esmLogFiltered(vec2 uv, vec2 uvDx, vec2 uvDy) {
  if (filterMode == kFilterBilinear || channelLevels == 1) return esmLogBilinear(uv, 0);
  vec2 dx = uvDx * float(shadowMapSize);
  vec2 dy = uvDy * float(shadowMapSize);
  float lengthX = length(dx);
  float lengthY = length(dy);
  float major = max(max(lengthX, lengthY), 1e-6f);
  float minor = max(min(lengthX, lengthY), 1e-6f);
  int probes = filterMode == kFilterAnisotropic ? clamp(int(ceil(major / minor)), 1, anisotropy) : 1;
  float lod = log2(major / float(probes));
  vec2 axis = (lengthX >= lengthY ? uvDx : uvDy);
  float acc = 0.0f;
  for (int k = 0; k < probes; ++k) {
    vec2 offset = axis * ((float(k) + 0.5f) / float(probes) - 0.5f);
    acc = esmLogAccumulate(acc, k == 0, esmLogTrilinear(uv + offset, lod), 1.0f / float(probes));
  }
  return acc;
}

#if ZMAX
layout(binding = 1) uniform sampler2DArray zmaxMap;
uniform int zmaxLevels;

// The largest depth under the lookup's footprint — the Z-max pyramid level whose texels cover the
// footprint (blur included), max of the 2x2 texels around the lookup — less the most the
// receiver's own plane rises across that region. Beyond the paper's constant offset: without
// this, every sloped receiver's own far side counts as an occluder behind it.
float zmaxUnderFootprint(vec2 uv, vec2 uvDx, vec2 uvDy, vec2 depthPerTexel) {
  vec2 footprint = max(abs(uvDx), abs(uvDy)) * float(shadowMapSize);
  float extent = max(max(footprint.x, footprint.y), float(2 * blurRadius + 1));
  int level = clamp(int(ceil(log2(max(extent, 1.0f)))), 0, zmaxLevels - 1);
  int size = max(shadowMapSize >> level, 1);
  ivec2 base = ivec2(floor(uv * float(size) - 0.5f));
  float zmax = 0.0f;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      ivec2 texel = clamp(base + ivec2(i, j), ivec2(0), ivec2(size - 1));
      zmax = max(zmax, texelFetch(zmaxMap, ivec3(texel, 0), level).x);
    }
  }
  float regionTexels = 2.0f * float(1 << level);
  return zmax - (abs(depthPerTexel.x) + abs(depthPerTexel.y)) * regionTexels;
}
#endif

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
void fetchChannels(vec2 uv, vec2 uvDx, vec2 uvDy, float receiverDepthForLayers,
                   inout float channels[kMaxChannels]) {
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
  if (technique == kTechniqueEsm && params.esm.filterSpace == kEsmFilterLog &&
      filterMode != kFilterPoint) {
    channels[0] = esmLogFiltered(uv, uvDx, uvDy);
    return;
  }
  // A layered technique reads the receiver's layer (and the next one, for LVSM's transition).
  int firstLayer = 0;
  int lastLayer = channelLayers - 1;
  if (technique == kTechniqueLvsm) {
    int layer = selectLayer(receiverDepthForLayers, params.lvsm.splits);
    firstLayer = (2 * layer) / 4;
    lastLayer = min((2 * layer + 3) / 4, channelLayers - 1);
  } else if (technique == kTechniquePowerCdf) {
    int layer = selectLayer(receiverDepthForLayers - params.powerCdf.depthBias, params.powerCdf.splits);
    firstLayer = (3 * layer) / 4;
    lastLayer = min((3 * layer + 2) / 4, channelLayers - 1);
  }
  for (int layer = firstLayer; layer <= lastLayer; ++layer) {
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
  float kernelSum = pcfKernelSum(pcf);  // once per lookup (pcf.h)
  for (int j = pcfFirstTap(pcf); j <= pcfLastTap(pcf); ++j) {
    for (int i = pcfFirstTap(pcf); i <= pcfLastTap(pcf); ++i) {
      float w = pcfTapWeightWithSum(i, j, fraction, pcf, kernelSum);
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

// ESM failure classification (ESM paper §3.3): true where the planar-receiver assumption fails.
bool esmFails(float filtered, float receiverDepth, vec2 uv, vec2 uvDx, vec2 uvDy,
              vec2 depthPerTexel) {
  if (params.esm.classifier == kEsmClassifyThreshold) {
    return esmFailsThreshold(filtered, receiverDepth, params.esm);
  }
#if ZMAX
  if (params.esm.classifier == kEsmClassifyZmax) {
    return esmFailsZmax(zmaxUnderFootprint(uv, uvDx, uvDy, depthPerTexel), receiverDepth,
                        params.esm);
  }
#endif
  return false;
}

// The ESM's 2x2 nearest level-0 texels and the lookup's bilinear fraction among them.
float esmFallback(vec2 uv, float receiverDepth) {
  vec2 position = uv * float(shadowMapSize) - 0.5f;
  ivec2 base = ivec2(floor(position));
  ivec2 last = ivec2(shadowMapSize - 1);
  vec4 stored = vec4(texelFetch(channelMap, ivec3(clamp(base, ivec2(0), last), 0), 0).x,
                     texelFetch(channelMap, ivec3(clamp(base + ivec2(1, 0), ivec2(0), last), 0), 0).x,
                     texelFetch(channelMap, ivec3(clamp(base + ivec2(0, 1), ivec2(0), last), 0), 0).x,
                     texelFetch(channelMap, ivec3(clamp(base + ivec2(1, 1), ivec2(0), last), 0), 0).x);
  return esmCustomPcf2x2(stored, position - vec2(base), receiverDepth, params.esm);
}

// Visibility at uv; `diagnostic` reports the technique's per-pixel state: 1 for an ESM pixel
// that failed classification, the layer index for LVSM, 0 otherwise.
float shadowVisibility(vec2 uv, float receiverDepth, vec2 uvDx, vec2 uvDy, vec2 depthPerTexel,
                       out float diagnostic) {
  diagnostic = 0.0f;
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
  fetchChannels(uv, uvDx, uvDy, receiverDepth, channels);
  if (technique == kTechniqueEsm &&
      esmFails(channels[0], receiverDepth, uv, uvDx, uvDy, depthPerTexel)) {
    diagnostic = 1.0f;
    return esmFallback(uv, receiverDepth);
  }
  if (technique == kTechniqueLvsm) diagnostic = float(selectLayer(receiverDepth, params.lvsm.splits));
  return reconstructVisibility(technique, channels, receiverDepth, params);
}

#endif
