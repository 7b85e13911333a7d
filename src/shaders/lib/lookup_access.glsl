// The GPU's side of the shared lookup (shared/lookup_access.h): the shadow map's textures as
// samplers and buffers, and the lookup's settings as a uniform block (shared/lookup_block.h,
// written by ShadowFilter), each at a binding a host may move. Everything else of the lookup and
// the filtered reference is shared/shadow_lookup.h and shared/filtered_reference.h.
#ifndef PENUMBRA_LIB_LOOKUP_ACCESS_GLSL
#define PENUMBRA_LIB_LOOKUP_ACCESS_GLSL
#include "technique_block.glsl"
#include "../shared/cascade_selection.h"
#include "../shared/filtered_reference.h"
#include "../shared/shadow_lookup.h"

#include "../shared/lookup_block.h"

// Bindings: a host moves them with these macros (ShadowBindings, ShadowFilter::shaderPreamble).
#ifndef PENUMBRA_CHANNEL_UNIT
#define PENUMBRA_CHANNEL_UNIT 0
#endif
#ifndef PENUMBRA_ZMAX_UNIT
#define PENUMBRA_ZMAX_UNIT 1
#endif
#ifndef PENUMBRA_DEPTH_UNIT
#define PENUMBRA_DEPTH_UNIT 2
#endif
#ifndef PENUMBRA_LOOKUP_BLOCK
#define PENUMBRA_LOOKUP_BLOCK 2
#endif
#ifndef PENUMBRA_SAT_STATS_BUFFER
#define PENUMBRA_SAT_STATS_BUFFER 2
#endif
#ifndef PENUMBRA_SAT_SUMS_BUFFER
#define PENUMBRA_SAT_SUMS_BUFFER 3
#endif
#ifndef PENUMBRA_BLUR_WEIGHTS_BUFFER
#define PENUMBRA_BLUR_WEIGHTS_BUFFER 4
#endif

// Every cascade's layers: cascade c's channel layer l is layer c * layersPerCascade + l.
layout(binding = PENUMBRA_CHANNEL_UNIT) uniform sampler2DArray penumbraChannelMap;
#if ZMAX
layout(binding = PENUMBRA_ZMAX_UNIT) uniform sampler2DArray penumbraZmaxMap;
#endif
#if MSAA
layout(binding = PENUMBRA_DEPTH_UNIT) uniform sampler2DMSArray penumbraDepthMap;
#else
layout(binding = PENUMBRA_DEPTH_UNIT) uniform sampler2DArray penumbraDepthMap;
#endif
#if SUMMED_AREA
#include "summed_area.glsl"
layout(std430, binding = PENUMBRA_SAT_STATS_BUFFER) readonly buffer SatStats {
  SatChannelStats penumbraSatStats[];
};
layout(std430, binding = PENUMBRA_SAT_SUMS_BUFFER) readonly buffer SatSums {
  uint64_t penumbraSatSums[];
};
#endif
// Per cascade, the prefilter's blur weights summed up to each tap (see blurCumulativeWeight).
layout(std430, binding = PENUMBRA_BLUR_WEIGHTS_BUFFER) readonly buffer BlurCumulative {
  float penumbraBlurWeights[];
};
// The lookup's settings (shared/lookup_block.h), written by ShadowFilter.
layout(std140, binding = PENUMBRA_LOOKUP_BLOCK) uniform PenumbraLookupBlock {
  LookupBlock penumbraLookup;
};

LookupSettings lookupSettings(int cascade) {
  LookupSettings s = lookupSettingsFromBlock(penumbraLookup, cascade);
#ifdef PENUMBRA_FILTER_MODE
  // The block's own mode, compiled in (lookupVariantDefines): the other modes' paths fold away
  // instead of sizing every pixel's registers.
  s.filterMode = PENUMBRA_FILTER_MODE;
#endif
#ifdef PENUMBRA_BLUR_KERNEL
  // The prefilter's kernel, compiled in where the renderer's camera pass defines it
  // (lookupParameterDefines): the kernel ESM's PCF fallback and the reference weigh their taps
  // with; llvmpipe evaluated every kernel's weights, the Gaussian's exponentials included, for
  // every tap.
  s.blurKernel = PENUMBRA_BLUR_KERNEL;
#endif
  return s;
}

// The technique's parameters as the lookup reads them: the block's, with those that choose
// among whole paths of the lookup compiled in where the renderer's camera pass defines them
// (gl/shadow_filter_state.h lookupParameterDefines: ESM's classifier, fallback and filter space;
// the blur kernel in lookupSettings),
// so the paths not taken fold away; llvmpipe ran every path, and ESM's camera pass took 6x its
// minimal lookup (3.5x compiled in). A host's preamble leaves them to the block.
TechniqueParams lookupParams() {
  TechniqueParams p = penumbraParams;
#ifdef PENUMBRA_ESM_CLASSIFIER
  p.esm.classifier = PENUMBRA_ESM_CLASSIFIER;
#endif
#ifdef PENUMBRA_ESM_FALLBACK
  p.esm.fallback = PENUMBRA_ESM_FALLBACK;
#endif
#ifdef PENUMBRA_ESM_FILTER_SPACE
  p.esm.filterSpace = PENUMBRA_ESM_FILTER_SPACE;
#endif
  return p;
}

int channelLayer(LookupSources s, int layer) {
  return s.cascade * penumbraLookup.layersPerCascade + layer;
}

vec4 channelTexel(LookupSources s, int layer, ivec2 texel, int level) {
  return texelFetch(penumbraChannelMap, ivec3(texel, channelLayer(s, layer)), level);
}

vec4 channelLinear(LookupSources s, int layer, vec2 uv, float lod) {
  return textureLod(penumbraChannelMap, vec3(uv, float(channelLayer(s, layer))), lod);
}

vec4 channelAnisotropic(LookupSources s, int layer, vec2 uv, vec2 uvDx, vec2 uvDy) {
  return textureGrad(penumbraChannelMap, vec3(uv, float(channelLayer(s, layer))), uvDx, uvDy);
}

float lightDepthTexel(LookupSources s, ivec2 texel) {
#if MSAA
  float z = 1.0f;
  for (int i = 0; i < penumbraLookup.depthSamples; ++i) {
    z = min(z, texelFetch(penumbraDepthMap, ivec3(texel, s.cascade), i).x);
  }
  return z;
#else
  return texelFetch(penumbraDepthMap, ivec3(texel, s.cascade), 0).x;
#endif
}

vec4 lightDepthQuad(LookupSources s, ivec2 texel, int size) {
#if MSAA
  return lightDepthQuadOfTexels(s, texel, size);  // no gather from a multisampled texture
#else
  // At the four texels' shared corner the gather's footprint is exactly them (its lower left at
  // floor(corner * size - 0.5) = texel, half a texel from any rounding), and the raw sampler's
  // clamp-to-edge clamps each as clampTexel. The gather's order is (0,1), (1,1), (1,0), (0,0).
  vec2 corner = vec2(texel + ivec2(1, 1)) / float(size);
  vec4 g = textureGather(penumbraDepthMap, vec3(corner, float(s.cascade)));
  return vec4(g.w, g.z, g.x, g.y);
#endif
}

float zmaxTexel(LookupSources s, ivec2 texel, int level) {
#if ZMAX
  return texelFetch(penumbraZmaxMap, ivec3(texel, s.cascade), level).x;
#else
  return 0.0f;
#endif
}

float blurCumulativeWeight(LookupSources s, int u) {
  int radius = int(penumbraLookup.layerKernel[s.cascade].x);
  return penumbraBlurWeights[s.cascade * (2 * kMaxBlurRadius + 1) + u + radius];
}

#if SUMMED_AREA
// Each cascade's channels are consecutive channels of one table (lib/summed_area.glsl).
uint64_t summedAreaPrefix(LookupSources s, int channel, int x, int y) {
  if (x < 0 || y < 0) return 0UL;
  return penumbraSatSums[satIndex(s.cascade * penumbraLookup.channelsPerCascade + channel, x, y,
                           ivec2(penumbraLookup.shadowMapSize))];
}

double summedAreaCentre(LookupSources s, int channel) {
  return penumbraSatStats[s.cascade * penumbraLookup.channelsPerCascade + channel].centre;
}

double summedAreaStep(LookupSources s, int channel) {
  return penumbraSatStats[s.cascade * penumbraLookup.channelsPerCascade + channel].step;
}
#endif

#endif
