// The camera pass's per-pixel shadow lookup, written once for the GPU and the CPU twin: the
// footprint picks the taps (lookup_footprint.h), the channels come filtered by the filter mode
// and their reduction, ESM failures take a fallback, and the dispatcher reconstructs visibility.
// Only texture access differs between the two sides (lookup_access.h).
#ifndef PENUMBRA_SHARED_SHADOW_LOOKUP_H
#define PENUMBRA_SHARED_SHADOW_LOOKUP_H
#include "cascade_selection.h"
#include "channel_reduction.h"
#include "lookup_access.h"
#include "lookup_footprint.h"
#include "mip_span.h"
#include "prelude.h"
#include "soft_shadow.h"
#include "summed_area.h"
#include "technique_dispatch.h"
PENUMBRA_BEGIN_SHARED

// Ties within this count as lit in the filtered reference and in the tests that match it: the
// receiver plane extended to a texel reproduces that texel's stored depth only to fp32 rounding.
const float kReferenceTie = 0.00002f;

struct FilteredChannels {
  float values[PENUMBRA_CHANNEL_CAPACITY];
};

// A texel layer's four channels, each reduced by its own reduction.
struct LayerAccumulator {
  ChannelAccumulator channels[4];
};

PENUMBRA_INLINE LayerAccumulator startLayerReduction(ivec4 reductions, float logExponent) {
  LayerAccumulator a;
  for (int k = 0; k < 4; ++k) a.channels[k] = startReduction(reductions[k], logExponent);
  return a;
}

PENUMBRA_INLINE vec4 layerReductionResult(LayerAccumulator a) {
  vec4 v = vec4(0.0f);
  for (int k = 0; k < 4; ++k) v[k] = reductionResult(a.channels[k]);
  return v;
}

// One bilinear lookup of a texel layer at a level, added to `a` with the lookup's share `weight`.
// Each texel is fetched once for its four channels (per channel, power-CDF's camera pass fetched
// every texel three times and took 4.5x its minimal lookup on llvmpipe).
PENUMBRA_INLINE LayerAccumulator accumulateBilinear(LookupSources s, LayerAccumulator a, int layer,
                                                    vec2 uv, int level, int levelSize,
                                                    float weight) {
  BilinearTaps taps = bilinearTaps(uv, levelSize);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      float w = weight * bilinearTapWeight(taps, i, j);
      if (w <= 0.0f) continue;
      vec4 v = channelTexel(s, layer, clampTexel(taps.base + ivec2(i, j), levelSize), level);
      for (int k = 0; k < 4; ++k) a.channels[k] = accumulateTap(a.channels[k], v[k], w);
    }
  }
  return a;
}

// A texel layer through the filter mode's taps, each channel reduced by its own reduction: what
// the hardware filter does for mean channels, done by hand for min/max (power-CDF) and log-space
// (ESM) channels, which a linear filter would get wrong.
PENUMBRA_INLINE vec4 filterLayerByTaps(LookupSources s, LookupSettings ls, int layer,
                                       ivec4 reductions, float logExponent, vec2 uv, vec2 uvDx,
                                       vec2 uvDy) {
  int size = ls.shadowMapSize;
  if (ls.filterMode == kFilterPoint) return channelTexel(s, layer, nearestTexel(uv, size), 0);
  LayerAccumulator a = startLayerReduction(reductions, logExponent);
  if (ls.filterMode == kFilterBilinear || ls.channelLevels == 1) {
    return layerReductionResult(accumulateBilinear(s, a, layer, uv, 0, size, 1.0f));
  }
  LookupProbes probes = lookupProbes(uvDx, uvDy, ls);
  TrilinearLevels levels = trilinearLevels(probes.lod, ls.channelLevels);
  float share = 1.0f / float(probes.count);
  for (int k = 0; k < probes.count; ++k) {
    vec2 at = uv + probeOffset(probes, k);
    a = accumulateBilinear(s, a, layer, at, levels.level, mipLevelSize(size, levels.level),
                           share * (1.0f - levels.fraction));
    a = accumulateBilinear(s, a, layer, at, levels.next, mipLevelSize(size, levels.next),
                           share * levels.fraction);
  }
  return layerReductionResult(a);
}

// A texel layer through the anisotropic probes the filtered reference models: trilinear lookups
// along the footprint's major axis, averaged (lookupProbes).
PENUMBRA_INLINE vec4 channelProbes(LookupSources s, LookupSettings ls, int layer, vec2 uv,
                                   vec2 uvDx, vec2 uvDy) {
  LookupProbes probes = lookupProbes(uvDx, uvDy, ls);
  vec4 v = vec4(0.0f);
  for (int k = 0; k < probes.count; ++k) {
    v += channelLinear(s, layer, uv + probeOffset(probes, k), probes.lod) / float(probes.count);
  }
  return v;
}

// One texel layer through the filter mode: where every channel read averages linearly
// (`linear`), the hardware's filter at the footprint's level (bilinear: level 0; point: the
// nearest texel; anisotropic: the probes, or the driver's own filter), else the taps by hand,
// each channel reduced by its own reduction. The production lookup's fetch, and the minimal
// lookup's (passes/minimal_lookup.frag): the least that filter mode reads.
PENUMBRA_INLINE vec4 filterLayer(LookupSources s, LookupSettings ls, int layer, bool linear,
                                 ivec4 reductions, float logExponent, vec2 uv, vec2 uvDx,
                                 vec2 uvDy) {
  if (!linear) return filterLayerByTaps(s, ls, layer, reductions, logExponent, uv, uvDx, uvDy);
  if (ls.filterMode == kFilterPoint) {
    return channelTexel(s, layer, nearestTexel(uv, ls.shadowMapSize), 0);
  }
  if (ls.filterMode == kFilterAnisotropicDriver)
    return channelAnisotropic(s, layer, uv, uvDx, uvDy);
  if (ls.filterMode == kFilterAnisotropic) return channelProbes(s, ls, layer, uv, uvDx, uvDy);
  float lod = ls.filterMode == kFilterBilinear ? 0.0f : lookupProbes(uvDx, uvDy, ls).lod;
  return channelLinear(s, layer, uv, lod);
}

#if PENUMBRA_SUMMED_AREA
// The table's continuous prefix sum at texel-edge coordinates (X, Y): bilinear between the
// integer prefix sums, since the channel is constant over each texel. Relative to `origin`, a
// prefix sum at or below every corner used; wrapped differences of the fixed-point sums are exact
// integers, and the bilinear form is taken on differences so that doubles keep every digit.
PENUMBRA_INLINE double summedAreaContinuousPrefix(LookupSources s, int channel, vec2 at,
                                                  uint64_t origin, int size) {
  ivec2 edge = ivec2(floor(at));
  double fx = double(at.x) - double(edge.x);
  double fy = double(at.y) - double(edge.y);
  int x1 = min(edge.x, size - 1);  // a corner on the far edge has weight 0 beyond it
  int y1 = min(edge.y, size - 1);
  uint64_t p00 = summedAreaPrefix(s, channel, edge.x - 1, edge.y - 1);
  uint64_t p10 = summedAreaPrefix(s, channel, x1, edge.y - 1);
  uint64_t p01 = summedAreaPrefix(s, channel, edge.x - 1, y1);
  uint64_t p11 = summedAreaPrefix(s, channel, x1, y1);
  double column = double(int64_t(p10 - p00));
  double row = double(int64_t(p01 - p00));
  double texel = double(int64_t(p11 - p10 - p01 + p00));
  return double(int64_t(p00 - origin)) + fx * column + fy * row + fx * fy * texel;
}

// Mean of a channel over a box with sub-texel corners (summed-area VSM, thesis §3.5, with
// bilinear corners so that a magnified box moves smoothly instead of snapping to texels).
PENUMBRA_INLINE float summedAreaBoxMean(LookupSources s, int channel, SummedAreaBox box, int size) {
  ivec2 lo = ivec2(floor(box.lo));
  uint64_t origin = summedAreaPrefix(s, channel, lo.x - 1, lo.y - 1);
  double sum = summedAreaContinuousPrefix(s, channel, box.hi, origin, size) -
               summedAreaContinuousPrefix(s, channel, vec2(box.lo.x, box.hi.y), origin, size) -
               summedAreaContinuousPrefix(s, channel, vec2(box.hi.x, box.lo.y), origin, size) +
               summedAreaContinuousPrefix(s, channel, box.lo, origin, size);
  double area = (double(box.hi.x) - double(box.lo.x)) * (double(box.hi.y) - double(box.lo.y));
  return float(summedAreaMean(sum, area, summedAreaStep(s, channel), summedAreaCentre(s, channel)));
}
#endif

// The technique's filtered channels at uv; only those the receiver's reconstruction reads are
// kept (layered techniques: the receiver's layers), the others stay 0.
PENUMBRA_INLINE FilteredChannels filterChannels(LookupSources s, LookupSettings ls, int technique,
                                                TechniqueParams p, vec2 uv, vec2 uvDx, vec2 uvDy,
                                                float receiverDepth) {
  FilteredChannels f;
  for (int i = 0; i < PENUMBRA_CHANNEL_CAPACITY; ++i) f.values[i] = 0.0f;
  ivec2 range = receiverChannelRange(technique, p, receiverDepth);
#if PENUMBRA_SUMMED_AREA
  if (ls.filterMode == kFilterSummedArea) {
    SummedAreaBox box = summedAreaBox(uv, uvDx, uvDy, ls);
    for (int c = range.x; c <= range.y; ++c) {
      f.values[c] = summedAreaBoxMean(s, c, box, ls.shadowMapSize);
    }
    return f;
  }
#endif
  // The techniques that read all their channels (all but LVSM and the power CDF), and the
  // layered two within two texel layers of capacity, loop over every layer of the capacity,
  // those outside the range fetched and left unread: the loop's count is then a constant, it
  // unrolls and indexes the channel array by constants. Over the range, a run-time count,
  // llvmpipe keeps the array in per-lane memory (scattered stores and loads for every channel):
  // CSM's camera pass took 1.7-2.5x its minimal lookup, the one-layer power CDF's 2.3-2.6x,
  // LVSM's 1.6-2.8x. More layers of LVSM or the power CDF keep the range, of which they read
  // one or two layers. A host's shader (capacity 48) and the CPU keep it too.
  bool readsAll = technique != kTechniqueLvsm && technique != kTechniquePowerCdf;
  bool everyLayer = PENUMBRA_CHANNEL_CAPACITY <= 32 && (readsAll || PENUMBRA_CHANNEL_CAPACITY <= 8);
  int fromLayer = everyLayer ? 0 : range.x / 4;
  int toLayer = everyLayer ? PENUMBRA_CHANNEL_CAPACITY / 4 - 1 : range.y / 4;
  for (int layer = fromLayer; layer <= toLayer; ++layer) {
    bool linear = true;  // every channel of this layer that is read averages linearly
    for (int k = 0; k < 4; ++k) {
      int c = 4 * layer + k;
      if (c >= range.x && c <= range.y && channelReduction(technique, c, p) != kReduceMean) {
        linear = false;
      }
    }
    ivec4 reductions = ivec4(kReduceMean);
    for (int k = 0; k < 4; ++k) reductions[k] = channelReduction(technique, 4 * layer + k, p);
    vec4 v = filterLayer(s, ls, layer, linear, reductions, p.esm.exponent, uv, uvDx, uvDy);
    for (int k = 0; k < 4; ++k) {
      int c = 4 * layer + k;
      if (c >= range.x && c <= range.y) f.values[c] = v[k];
    }
  }
  return f;
}

// The soft variant's filtered channels for the mip-mapped filter modes: the box of `width` texels
// (the penumbra) as kSoftProbeSide^2 probes (soft_shadow.h), each channel reduced over them by its
// own reduction (mean, min, max or log-space mean).
PENUMBRA_INLINE FilteredChannels softFilterChannels(LookupSources s, LookupSettings ls,
                                                    int technique, TechniqueParams p, vec2 uv,
                                                    float width, float receiverDepth) {
  int size = ls.shadowMapSize;
  SoftFootprint probe =
      softFootprint(vec2(0.0f), vec2(0.0f), width / float(kSoftProbeSide), size, ls.filterMode);
  ivec2 range = receiverChannelRange(technique, p, receiverDepth);
  ChannelAccumulator acc[PENUMBRA_CHANNEL_CAPACITY];
  for (int c = range.x; c <= range.y; ++c) {
    acc[c] = startReduction(channelReduction(technique, c, p), p.esm.exponent);
  }
  float share = 1.0f / float(kSoftProbeSide * kSoftProbeSide);
  for (int j = 0; j < kSoftProbeSide; ++j) {
    for (int i = 0; i < kSoftProbeSide; ++i) {
      vec2 at = uv + softProbeOffset(i, j, width, size);
      FilteredChannels f =
          filterChannels(s, ls, technique, p, at, probe.uvDx, probe.uvDy, receiverDepth);
      for (int c = range.x; c <= range.y; ++c) acc[c] = accumulateTap(acc[c], f.values[c], share);
    }
  }
  FilteredChannels result;
  for (int c = 0; c < PENUMBRA_CHANNEL_CAPACITY; ++c) result.values[c] = 0.0f;
  for (int c = range.x; c <= range.y; ++c) result.values[c] = reductionResult(acc[c]);
  return result;
}

// A light-depth quad (lightDepthQuad) texel by texel: the CPU's, and the GPU's where a
// multisampled depth has no gather.
PENUMBRA_INLINE vec4 lightDepthQuadOfTexels(LookupSources s, ivec2 texel, int size) {
  return vec4(lightDepthTexel(s, clampTexel(texel, size)),
              lightDepthTexel(s, clampTexel(texel + ivec2(1, 0), size)),
              lightDepthTexel(s, clampTexel(texel + ivec2(0, 1), size)),
              lightDepthTexel(s, clampTexel(texel + ivec2(1, 1), size)));
}

// PCF (or the hard test, a 1-tap PCF) over the light pass's depth, which no prefilter touches:
// the map of PCF and the hard test, and ESM's fallback. depthPerTexel is the receiver plane's
// depth gradient per shadow-map texel (receiver-plane depth bias). `quads`: the taps 2x2 at a time,
// one quad each (lightDepthQuad; a quad's taps beyond an odd tap count weigh 0 and are skipped),
// else tap by tap. On llvmpipe (480x270, 1024^2, backyard, four alternating runs) the quads took
// ESM's camera pass, whose fallback is paid by every pixel, from 10.6-11.1 ms to 8.8-10.8, and
// PCF's from 25-31 ms to 35-56: ESM's fallback reads quads, PCF and the hard test single taps.
PENUMBRA_INLINE float pcfLookup(LookupSources s, int size, bool quads, vec2 uv, float receiverDepth,
                                vec2 depthPerTexel, PcfParams pcf) {
  vec2 position = uv * float(size);
  bool bilinear = kernelHasBilinearTent(pcf.kernel);
  vec2 origin = bilinear ? floor(position - 0.5f) : floor(position);
  vec2 fraction = bilinear ? position - 0.5f - origin : vec2(0.0f);
  float slope = abs(depthPerTexel.x) + abs(depthPerTexel.y);
  float lit = 0.0f;
  float kernelSum = pcfKernelSum(pcf);  // once per lookup (pcf.h)
  int step = quads ? 2 : 1;
  for (int j = pcfFirstTap(pcf); j <= pcfLastTap(pcf); j += step) {
    for (int i = pcfFirstTap(pcf); i <= pcfLastTap(pcf); i += step) {
      vec2 corner = origin + vec2(float(i), float(j));
      vec4 quad = quads ? lightDepthQuad(s, ivec2(corner), size) : vec4(0.0f);
      for (int k = 0; k < step * step; ++k) {
        ivec2 offset = ivec2(k % step, k / step);
        float w = pcfTapWeightWithSum(i + offset.x, j + offset.y, fraction, pcf, kernelSum);
        if (w <= 0.0f) continue;
        vec2 tap = corner + vec2(offset);
        float z = quads ? quad[k] : lightDepthTexel(s, clampTexel(ivec2(tap), size));
        float d = receiverDepth;
        if (pcf.receiverPlane != 0) d += dot(depthPerTexel, tap + 0.5f - position);
        lit += w * hardVisibility(z, biasedReceiverDepth(d, slope, pcf.bias));
      }
    }
  }
  return clamp(lit, 0.0f, 1.0f);  // the weights sum to 1 up to fp32 rounding
}

// PCF with the prefilter's own kernel (the blur convolved with the bilinear tent, or the blur
// alone for point lookups), the receiver plane and the reference's tie: the filtered reference
// itself for point and bilinear lookups (docs/reference.md).
PENUMBRA_INLINE PcfParams pcfMatchingPrefilter(LookupSettings ls) {
  PcfParams p;
  bool point = ls.filterMode == kFilterPoint;
  if (ls.blurKernel == kKernelGaussian) {
    p.kernel = point ? kKernelGaussian : kKernelGaussianBilinear;
  } else {
    p.kernel = point ? kKernelBox : kKernelBilinear;
  }
  p.radius = ls.blurRadius;
  p.sigma = ls.blurSigma;
  p.receiverPlane = 1;
  p.bias.constantBias = kReferenceTie;
  p.bias.slopeScaledBias = 0.0f;
  p.bias.pad0 = 0.0f;
  p.bias.pad1 = 0.0f;
  return p;
}

// The largest depth under the lookup's footprint (blur included) from the Z-max pyramid: the
// level whose texels cover the footprint, max of the 2x2 texels around the lookup; less the most
// the receiver's own plane rises across that region. Beyond the paper's constant offset: without
// it, every sloped receiver's own far side counts as an occluder behind it.
PENUMBRA_INLINE float zmaxUnderFootprint(LookupSources s, LookupSettings ls, vec2 uv, vec2 uvDx,
                                         vec2 uvDy, vec2 depthPerTexel) {
  vec2 footprint = max(abs(uvDx), abs(uvDy)) * float(ls.shadowMapSize);
  float extent = max(max(footprint.x, footprint.y), float(2 * ls.blurRadius + 1));
  int level = clamp(int(ceil(log2(max(extent, 1.0f)))), 0, ls.zmaxLevels - 1);
  int size = mipLevelSize(ls.shadowMapSize, level);
  BilinearTaps taps = bilinearTaps(uv, size);
  float zmax = 0.0f;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      zmax = max(zmax, zmaxTexel(s, clampTexel(taps.base + ivec2(i, j), size), level));
    }
  }
  float regionTexels = 2.0f * float(1 << level);
  return zmax - (abs(depthPerTexel.x) + abs(depthPerTexel.y)) * regionTexels;
}

// ESM failure classification (ESM paper §3.3): true where the planar-receiver assumption fails.
PENUMBRA_INLINE bool esmFails(LookupSources s, LookupSettings ls, EsmParams esm, float filtered,
                              float receiverDepth, vec2 uv, vec2 uvDx, vec2 uvDy,
                              vec2 depthPerTexel) {
  if (esm.classifier == kEsmClassifyThreshold) {
    return esmFailsThreshold(filtered, receiverDepth, esm);
  }
  if (esm.classifier == kEsmClassifyZmax && ls.zmaxLevels > 0) {
    return esmFailsZmax(zmaxUnderFootprint(s, ls, uv, uvDx, uvDy, depthPerTexel), receiverDepth,
                        esm);
  }
  return false;
}

// The paper's fallback exactly as written (ESM paper §3.3): the clamped ESM test at the 4
// nearest texels of the (prefiltered) ESM, bilinearly interpolated. It cannot undo the
// prefilter's convolution (§3.4).
PENUMBRA_INLINE float esmPaperFallback(LookupSources s, LookupSettings ls, EsmParams esm, vec2 uv,
                                       float receiverDepth) {
  BilinearTaps taps = bilinearTaps(uv, ls.shadowMapSize);
  float lit = 0.0f;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      ivec2 texel = clampTexel(taps.base + ivec2(i, j), ls.shadowMapSize);
      float stored = channelTexel(s, 0, texel, 0).x;
      lit += bilinearTapWeight(taps, i, j) * esmVisibility(stored, receiverDepth, esm);
    }
  }
  return lit;
}

// The default fallback (kEsmFallbackPcf): PCF of the light pass's depth, which the prefilter never
// touched, under the kernel the lookup filters with. Hard lights: the prefilter's own kernel (the
// filtered reference itself for point and bilinear lookups; mip-mapped and summed-area lookups
// widen their kernel with the footprint where PCF keeps the blur's, docs/techniques.md). Area
// lights: PCSS's box of the penumbra's width, the kernel the widened filter stands for (the blur's
// own 2x2 test would put a hard edge inside a soft penumbra). penumbraTexels < 0: a hard light.
PENUMBRA_INLINE float esmPcfFallback(LookupSources s, LookupSettings ls, vec2 uv,
                                     float receiverDepth, vec2 depthPerTexel,
                                     float penumbraTexels) {
  PcfParams pcf = pcfMatchingPrefilter(ls);
#if PENUMBRA_SOFT_SHADOWS
  if (penumbraTexels >= 0.0f) {
    return pcssVisibility(s, ls.shadowMapSize, uv, receiverDepth, depthPerTexel, pcf.receiverPlane,
                          pcf.bias, penumbraTexels);
  }
#endif
  return pcfLookup(s, ls.shadowMapSize, true, uv, receiverDepth, depthPerTexel, pcf);
}

// Visibility and the technique's per-pixel state: 1 for an ESM pixel that failed classification,
// the layer index for LVSM, 0 otherwise.
struct ShadowSample {
  float visibility;
  float diagnostic;
};

// The whole lookup for a receiver at uv (its screen derivatives uvDx, uvDy) and linear light-space
// depth receiverDepth (clamped to [0,1]), with the receiver plane's depth gradient per texel.
// A light with a size (soft_shadow.h) makes PCF PCSS and widens every filterable technique's
// footprint to the penumbra its blocker search estimates; the hard test stays hard.
PENUMBRA_INLINE ShadowSample shadowLookup(LookupSources s, LookupSettings ls, int technique,
                                          TechniqueParams p, vec2 uv, float receiverDepth,
                                          vec2 uvDx, vec2 uvDy, vec2 depthPerTexel,
                                          SoftLight light) {
  ShadowSample r;
  r.diagnostic = 0.0f;
  float d = clamp(receiverDepth, 0.0f, 1.0f);
  bool softProbes = false;  // the penumbra, not the pixel's footprint, sets the filter width
  float softWidth = 0.0f;
  float penumbra = -1.0f;  // area lights: the penumbra's width in texels, blur included
#if PENUMBRA_SOFT_SHADOWS
  if (light.size > 0.0f && technique != kTechniqueHard) {
    BlockerEstimate blockers = searchBlockers(s, ls.shadowMapSize, light, uv, d, depthPerTexel);
    if (blockers.share == 0.0f) {
      r.visibility = 1.0f;  // nothing between the receiver and any point of the light
      return r;
    }
    float width = softFilterTexels(light, d, blockers);
    penumbra = width;
    if (technique == kTechniquePcf) {
      r.visibility = pcssVisibility(s, ls.shadowMapSize, uv, d, depthPerTexel, p.pcf.receiverPlane,
                                    p.pcf.bias, width);
      return r;
    }
    // The summed-area box replaces the blur (its minimum is the blur's width); the mip probes
    // come after it.
    if (ls.filterMode != kFilterSummedArea) width = softWidthBeyondBlur(width, ls);
    SoftFootprint footprint = softFootprint(uvDx, uvDy, width, ls.shadowMapSize, ls.filterMode);
    softProbes = ls.filterMode != kFilterSummedArea && any(notEqual(footprint.uvDx, uvDx));
    softWidth = width;
    uvDx = footprint.uvDx;
    uvDy = footprint.uvDy;
  }
#endif
#if PENUMBRA_COMPILES_TECHNIQUE(PENUMBRA_TECHNIQUE_HARD) || \
    PENUMBRA_COMPILES_TECHNIQUE(PENUMBRA_TECHNIQUE_PCF)
  if (!techniquePrefiltersChannels(technique)) {
    PcfParams pcf = p.pcf;
    pcf.radius = worldConstantKernelRadius(pcf.radius, ls.kernelScale);
    pcf.sigma = worldConstantKernelSigma(pcf.sigma, ls.kernelScale);
    if (technique == kTechniqueHard) {
      pcf.kernel = kKernelBox;
      pcf.radius = 0;
      pcf.receiverPlane = 0;
      pcf.bias = p.hard;
    }
    r.visibility = pcfLookup(s, ls.shadowMapSize, false, uv, d, depthPerTexel, pcf);
    return r;
  }
#endif
#if PENUMBRA_SOFT_SHADOWS
  FilteredChannels f = softProbes ? softFilterChannels(s, ls, technique, p, uv, softWidth, d)
                                  : filterChannels(s, ls, technique, p, uv, uvDx, uvDy, d);
#else
  FilteredChannels f = filterChannels(s, ls, technique, p, uv, uvDx, uvDy, d);
#endif
#if PENUMBRA_COMPILES_TECHNIQUE(PENUMBRA_TECHNIQUE_ESM)
  if (technique == kTechniqueEsm &&
      esmFails(s, ls, p.esm, f.values[0], d, uv, uvDx, uvDy, depthPerTexel)) {
    r.diagnostic = 1.0f;
    if (p.esm.fallback == kEsmFallbackPaper) {
      r.visibility = esmPaperFallback(s, ls, p.esm, uv, d);
    } else {
      r.visibility = esmPcfFallback(s, ls, uv, d, depthPerTexel, penumbra);
    }
    return r;
  }
#endif
  if (technique == kTechniqueLvsm) r.diagnostic = float(selectLayer(d, p.lvsm.splits));
  if (technique == kTechniquePowerCdf) r.diagnostic = float(powerCdfReceiverLayer(d, p.powerCdf));
  r.visibility = reconstructVisibility(technique, f.values, d, p);
  return r;
}

PENUMBRA_END_SHARED
#endif
