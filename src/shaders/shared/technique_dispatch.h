// One dispatcher over the closed set of techniques, on flat channel arrays: how many channels a
// technique stores, how each is encoded from depth and reduced when filtered, and how the
// filtered channels become visibility. The C++ reference and the GPU parity test both run it.
#ifndef PENUMBRA_SHARED_TECHNIQUE_DISPATCH_H
#define PENUMBRA_SHARED_TECHNIQUE_DISPATCH_H
#include "constants.h"
#include "prelude.h"
#include "technique_params.h"
PENUMBRA_BEGIN_SHARED

// The size of a lookup's channel arrays (FilteredChannels, reconstructVisibility): every channel
// a technique may store, unless a shader compiled for one technique and its parameters defines
// its own channels, in whole texel layers (gl/shadow_filter_state.h channelCapacityDefine). A
// dynamically indexed array lives in per-lane memory on llvmpipe, where zeroing and copying 48
// floats a pixel took LVSM's camera pass to 3.2x its minimal lookup, the power CDF's to 4.3x.
#ifndef PENUMBRA_CHANNEL_CAPACITY
#define PENUMBRA_CHANNEL_CAPACITY kMaxChannels
#endif

PENUMBRA_INLINE int techniqueChannelCount(int technique, TechniqueParams p) {
  if (technique == kTechniqueVsm || technique == kTechniqueEvsm2) return 2;
  if (technique == kTechniqueLvsm) return 2 * p.lvsm.splits.layerCount;
  if (technique == kTechniqueEvsm4 || technique == kTechniqueMsm) return 4;
  if (technique == kTechniqueCsm) return 2 * p.csm.termCount;
  if (technique == kTechniquePowerCdf) return 3 * p.powerCdf.splits.layerCount;
  return 1;  // hard, PCF and ESM store one value
}

// True where the filter must run after the test (PCF): its channel is raw depth.
PENUMBRA_INLINE bool techniqueFiltersAfterTest(int technique) {
  return technique == kTechniquePcf;
}

// True where depth is encoded into channels filtered before the test (blur, mips, summed-area
// table): every technique but PCF (filters after the test) and the hard test (no filter), whose
// one channel is the raw depth. The GPU passes, the lookup and the CPU (prefiltersChannels) ask
// this.
PENUMBRA_INLINE bool techniquePrefiltersChannels(int technique) {
  return !techniqueFiltersAfterTest(technique) && technique != kTechniqueHard;
}

// A depth's walk over its channel texture's layers, in order: CSM's basis waves rotate from one
// texture to the next (csmBasisWalk) instead of evaluating every term's sine and cosine.
struct TexelEncoding {
  float depth;
  int texelLayer;
  CsmBasisWalk csm;  // CSM: at texture texelLayer
};

PENUMBRA_INLINE TexelEncoding startTexelEncoding(int technique, float depth, TechniqueParams p) {
  TexelEncoding e;
  e.depth = depth;
  e.texelLayer = 0;
  if (technique == kTechniqueCsm) {
    e.csm = csmBasisWalkStart(depth, p.csm);
  } else {
    e.csm.terms = vec4(0.0f);
    e.csm.previous = vec4(0.0f);
    e.csm.twiceCosStep = 0.0f;
  }
  return e;
}

PENUMBRA_INLINE TexelEncoding nextTexelLayer(int technique, TexelEncoding e) {
  TexelEncoding next = e;
  next.texelLayer = e.texelLayer + 1;
  if (technique == kTechniqueCsm) next.csm = csmBasisWalkNext(e.csm);
  return next;
}

// The layer intervals texel layer `texelLayer` encodes into: LVSM's two layers' warp ranges,
// or the power CDF's first and second layer's clamp ranges (a texel spans at most two of its
// three-channel layers), as (lower, upper, lower, upper); (0, 1, 0, 1) for other techniques.
// They depend on the parameters only, so the renderer computes them once per frame into a
// uniform block (lib/technique_block.glsl): a dynamically indexed split array in a by-value
// struct costs llvmpipe per-lane gathers, and made LVSM's encode 7x a copy (issue 12).
PENUMBRA_INLINE vec4 texelLayerRanges(int technique, int texelLayer, TechniqueParams p) {
  vec4 ranges = vec4(0.0f, 1.0f, 0.0f, 1.0f);
  if (technique == kTechniqueLvsm) {
    ranges = lvsmTexelLayerRanges(texelLayer, p.lvsm.splits, p.lvsm.overlap);
  } else if (technique == kTechniquePowerCdf) {
    int last = p.powerCdf.splits.layerCount - 1;
    int firstLayer = (4 * texelLayer) / 3;
    vec2 a = powerCdfLayerRange(min(firstLayer, last), p.powerCdf);
    vec2 b = powerCdfLayerRange(min(firstLayer + 1, last), p.powerCdf);
    ranges = vec4(a.x, a.y, b.x, b.y);
  }
  return ranges;
}

// Every texel layer's ranges, as the uniform block holds them.
struct TexelLayerRangeTable {
  vec4 texelLayer[kMaxTexelLayers];
};

PENUMBRA_INLINE TexelLayerRangeTable texelLayerRangeTable(int technique, TechniqueParams p) {
  TexelLayerRangeTable table;
  for (int t = 0; t < kMaxTexelLayers; ++t) table.texelLayer[t] = texelLayerRanges(technique, t, p);
  return table;
}

// Channels 4*texelLayer .. 4*texelLayer+3 of one depth: one texel of the channel texture's layer
// `texelLayer` (`ranges`: its texelLayerRanges), encoded at once so that a warp's exponentials
// or the moments' powers are computed once per texel, not once per channel. Components beyond
// the technique's channels are 0.
PENUMBRA_INLINE vec4 encodeCurrentTexelLayer(int technique, TexelEncoding e, vec4 ranges,
                                             TechniqueParams p) {
  float depth = e.depth;
  int texelLayer = e.texelLayer;
  vec4 v = vec4(0.0f);
  if (technique == kTechniqueVsm) {
    vec2 m = vsmEncode(depth);
    v = vec4(m.x, m.y, 0.0f, 0.0f);
  } else if (technique == kTechniqueLvsm) {  // two layers' moments per texel
    vec2 a = lvsmEncodeInRange(depth, vec2(ranges[0], ranges[1]));
    vec2 b = lvsmEncodeInRange(depth, vec2(ranges[2], ranges[3]));
    v = vec4(a.x, a.y, b.x, b.y);
  } else if (technique == kTechniqueEvsm2 || technique == kTechniqueEvsm4) {
    v = evsmEncode(depth, p.evsm);
  } else if (technique == kTechniqueEsm) {
    v = vec4(esmEncode(depth, p.esm), 0.0f, 0.0f, 0.0f);
  } else if (technique == kTechniqueCsm) {
    v = csmBasisTexture(e.csm);
  } else if (technique == kTechniquePowerCdf) {
    // Three channels per layer, four per texel: a texel spans at most two layers.
    int firstLayer = (4 * texelLayer) / 3;
    float first = powerCdfDepthInRange(depth, vec2(ranges[0], ranges[1]));
    float second = powerCdfDepthInRange(depth, vec2(ranges[2], ranges[3]));
    for (int c = 0; c < 4; ++c) v[c] = (4 * texelLayer + c) / 3 == firstLayer ? first : second;
  } else if (technique == kTechniqueMsm) {
    v = msmEncode(depth, p.msm);
  } else {
    v = vec4(depth, 0.0f, 0.0f, 0.0f);  // hard and PCF store the depth
  }
  int count = techniqueChannelCount(technique, p);
  for (int c = 0; c < 4; ++c) {
    if (4 * texelLayer + c >= count) v[c] = 0.0f;
  }
  // Precise: the fused prefilter's blur, precise (channel_reduction.h), makes every value that
  // flows into it precise, its encode included (GLSL's precise reaches back through them); the
  // separate encode pass must round as it does, or the two paths part by an ulp of the exponent.
  PENUMBRA_PRECISE vec4 encoded = v;
  return encoded;
}

// The walk at texel layer `texelLayer`, for passes that encode one layer at a time.
PENUMBRA_INLINE TexelEncoding texelEncodingAt(int technique, float depth, int texelLayer,
                                              TechniqueParams p) {
  TexelEncoding e = startTexelEncoding(technique, depth, p);
  for (int i = 0; i < texelLayer; ++i) e = nextTexelLayer(technique, e);
  return e;
}

// Texel layer `texelLayer` of a depth alone, by the same walk and ranges.
PENUMBRA_INLINE vec4 encodeTexelLayer(int technique, float depth, int texelLayer,
                                      TechniqueParams p) {
  return encodeCurrentTexelLayer(technique, texelEncodingAt(technique, depth, texelLayer, p),
                                 texelLayerRanges(technique, texelLayer, p), p);
}

PENUMBRA_INLINE int channelReduction(int technique, int channel, TechniqueParams p) {
  if (technique == kTechniquePowerCdf) {
    int role = channel % 3;
    return role == 0 ? kReduceMin : (role == 1 ? kReduceMax : kReduceMean);
  }
  if (technique == kTechniqueEsm && p.esm.filterSpace == kEsmFilterLog) return kReduceLogMeanExp;
  return kReduceMean;
}

// The channels [x, y] that reconstructVisibility reads for a receiver at `receiverDepth`: the
// receiver's layer (and LVSM's next one, for its transition) for the layered techniques, all
// channels otherwise. The lookup keeps only these (and with more than two texel layers fetches
// only their layers, shadow_lookup.h filterChannels).
PENUMBRA_INLINE ivec2 receiverChannelRange(int technique, TechniqueParams p, float receiverDepth) {
  if (technique == kTechniqueLvsm) {
    int layer = selectLayer(receiverDepth, p.lvsm.splits);
    int next = min(layer + 1, p.lvsm.splits.layerCount - 1);
    return ivec2(2 * layer, 2 * next + 1);
  }
  if (technique == kTechniquePowerCdf) {
    int layer = selectLayer(receiverDepth - p.powerCdf.depthBias, p.powerCdf.splits);
    return ivec2(3 * layer, 3 * layer + 2);
  }
  return ivec2(0, techniqueChannelCount(technique, p) - 1);
}

// Visibility in [0,1] of a receiver at `receiverDepth` (linear light-space depth in [0,1]) from
// the technique's filtered channels. For PCF and the hard test the channel is one depth texel.
PENUMBRA_INLINE float reconstructVisibility(int technique,
                                            float channels[PENUMBRA_CHANNEL_CAPACITY],
                                            float receiverDepth, TechniqueParams p) {
  if (!techniquePrefiltersChannels(technique)) {
    HardParams bias = technique == kTechniqueHard ? p.hard : p.pcf.bias;
    return hardVisibility(channels[0], biasedReceiverDepth(receiverDepth, 0.0f, bias));
  }
  if (technique == kTechniqueVsm) {
    return vsmVisibility(vec2(channels[0], channels[1]), receiverDepth, p.vsm);
  }
  if (technique == kTechniqueLvsm) {
    int layer = selectLayer(receiverDepth, p.lvsm.splits);
    int next = min(layer + 1, p.lvsm.splits.layerCount - 1);
    vec2 moments = vec2(channels[2 * layer], channels[2 * layer + 1]);
    vec2 nextMoments = vec2(channels[2 * next], channels[2 * next + 1]);
    return lvsmVisibility(moments, nextMoments, receiverDepth, p.lvsm);
  }
  if (technique == kTechniqueEvsm2) {
    return evsm2Visibility(vec2(channels[0], channels[1]), receiverDepth, p.evsm);
  }
  if (technique == kTechniqueEvsm4) {
    vec4 moments = vec4(channels[0], channels[1], channels[2], channels[3]);
    return evsm4Visibility(moments, receiverDepth, p.evsm);
  }
  if (technique == kTechniqueEsm) return esmVisibility(channels[0], receiverDepth, p.esm);
  if (technique == kTechniqueCsm) {
    vec4 basis[8];
    for (int i = 0; i < 8; ++i) {
      basis[i] = vec4(0.5f);
    }
    for (int i = 0; i < 2 * p.csm.termCount; ++i) {
      basis[i / 4][i % 4] = channels[i];
    }
    return csmVisibility(basis, receiverDepth, p.csm);
  }
  if (technique == kTechniquePowerCdf) {
    int layer = selectLayer(receiverDepth - p.powerCdf.depthBias, p.powerCdf.splits);
    vec3 stats = vec3(channels[3 * layer], channels[3 * layer + 1], channels[3 * layer + 2]);
    return powerCdfVisibility(stats, receiverDepth, p.powerCdf);
  }
  if (technique == kTechniqueMsm) {
    vec4 moments = vec4(channels[0], channels[1], channels[2], channels[3]);
    return msmVisibility(moments, receiverDepth, p.msm);
  }
  return 1.0f;  // an unknown id: lit, a defined value (the C++ entry points reject such ids)
}

PENUMBRA_END_SHARED
#endif
