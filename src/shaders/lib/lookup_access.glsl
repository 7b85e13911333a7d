// The GPU's side of the shared lookup (shared/lookup_access.h): the shadow map's textures as
// samplers and buffers, and the lookup's settings as uniforms. Everything else of the lookup and
// the filtered reference is shared/shadow_lookup.h and shared/filtered_reference.h.
#ifndef PENUMBRA_LIB_LOOKUP_ACCESS_GLSL
#define PENUMBRA_LIB_LOOKUP_ACCESS_GLSL
#include "technique_block.glsl"
#include "../shared/cascade_selection.h"
#include "../shared/filtered_reference.h"
#include "../shared/shadow_lookup.h"

// Every cascade's layers: cascade c's channel layer l is layer c * layersPerCascade + l.
layout(binding = 0) uniform sampler2DArray channelMap;
#if ZMAX
layout(binding = 1) uniform sampler2DArray zmaxMap;
#endif
#if MSAA
layout(binding = 2) uniform sampler2DMSArray lightDepthMap;
uniform int lightSamples;
#else
layout(binding = 2) uniform sampler2DArray lightDepthMap;
#endif
#if SUMMED_AREA
#include "summed_area.glsl"
layout(std430, binding = 2) readonly buffer SatStats { SatChannelStats satStats[]; };
layout(std430, binding = 3) readonly buffer SatSums { uint64_t satSums[]; };
#endif
// Per cascade, the prefilter's blur weights summed up to each tap (see blurCumulativeWeight).
layout(std430, binding = 4) readonly buffer BlurCumulative { float blurCumulative[]; };

uniform int filterMode;
uniform int shadowMapSize;
uniform int channelLevels;
uniform int anisotropy;
uniform int blurKernel;
uniform int blurRadius[kMaxCascades];  // per cascade: the kernel is constant in world units
uniform float blurSigma[kMaxCascades];
uniform float kernelScale[kMaxCascades];  // cascade 0's texel over cascade c's
uniform int zmaxLevels;
uniform int layersPerCascade;
uniform int channelsPerCascade;

LookupSettings lookupSettings(int cascade) {
  LookupSettings s;
  s.filterMode = filterMode;
  s.shadowMapSize = shadowMapSize;
  s.channelLevels = channelLevels;
  s.anisotropy = anisotropy;
  s.blurKernel = blurKernel;
  s.blurRadius = blurRadius[cascade];
  s.blurSigma = blurSigma[cascade];
  s.zmaxLevels = zmaxLevels;
  s.kernelScale = kernelScale[cascade];
  return s;
}

vec4 channelTexel(LookupSources s, int layer, ivec2 texel, int level) {
  return texelFetch(channelMap, ivec3(texel, s.cascade * layersPerCascade + layer), level);
}

vec4 channelLinear(LookupSources s, int layer, vec2 uv, float lod) {
  return textureLod(channelMap, vec3(uv, float(s.cascade * layersPerCascade + layer)), lod);
}

vec4 channelAnisotropic(LookupSources s, int layer, vec2 uv, vec2 uvDx, vec2 uvDy) {
  return textureGrad(channelMap, vec3(uv, float(s.cascade * layersPerCascade + layer)), uvDx,
                     uvDy);
}

float lightDepthTexel(LookupSources s, ivec2 texel) {
#if MSAA
  float z = 1.0f;
  for (int i = 0; i < lightSamples; ++i) {
    z = min(z, texelFetch(lightDepthMap, ivec3(texel, s.cascade), i).x);
  }
  return z;
#else
  return texelFetch(lightDepthMap, ivec3(texel, s.cascade), 0).x;
#endif
}

float zmaxTexel(LookupSources s, ivec2 texel, int level) {
#if ZMAX
  return texelFetch(zmaxMap, ivec3(texel, s.cascade), level).x;
#else
  return 0.0f;
#endif
}

float blurCumulativeWeight(LookupSources s, int u) {
  return blurCumulative[s.cascade * (2 * kMaxBlurRadius + 1) + u + blurRadius[s.cascade]];
}

#if SUMMED_AREA
// Each cascade's channels are consecutive channels of one table (lib/summed_area.glsl).
uint64_t summedAreaPrefix(LookupSources s, int channel, int x, int y) {
  if (x < 0 || y < 0) return 0UL;
  return satSums[satIndex(s.cascade * channelsPerCascade + channel, x, y, ivec2(shadowMapSize))];
}

double summedAreaCentre(LookupSources s, int channel) {
  return satStats[s.cascade * channelsPerCascade + channel].centre;
}

double summedAreaStep(LookupSources s, int channel) {
  return satStats[s.cascade * channelsPerCascade + channel].step;
}
#endif

#endif
