// The filtered reference (docs/reference.md): the exact PCF of the raw depth map under the
// effective kernel a technique's prefilter and lookup apply -- the blur at level 0, averaged over
// each mip texel's block, weighted by the lookup's taps -- with every level-0 texel tested once
// against the receiver's plane extended to it. Exact at every level and box size: the kernel is
// separable per lookup level, so each texel of its support is weighted in closed form.
#ifndef PENUMBRA_SHARED_FILTERED_REFERENCE_H
#define PENUMBRA_SHARED_FILTERED_REFERENCE_H
#include "lookup_access.h"
#include "lookup_footprint.h"
#include "mip_span.h"
#include "prelude.h"
#include "shadow_lookup.h"
PENUMBRA_BEGIN_SHARED

// The shadow test of level-0 texel v for a receiver plane through `position` (level-0 texels).
// v may lie outside the map, where the blur's clamp-to-edge reads the edge texel's depth; the
// receiver plane is still evaluated at v.
PENUMBRA_INLINE float referenceTexelTest(LookupSources s, int size, ivec2 v, vec2 position,
                                         float receiverDepth, vec2 depthPerTexel) {
  float z = lightDepthTexel(s, clampTexel(v, size));
  float d = receiverDepth + dot(depthPerTexel, vec2(v) + 0.5f - position);
  return z >= d - kReferenceTie ? 1.0f : 0.0f;
}

// The blur's taps -r..u summed: 0 below the kernel, every tap above it.
PENUMBRA_INLINE float cumulativeBlur(LookupSources s, int u, int radius) {
  if (u < -radius) return 0.0f;
  return blurCumulativeWeight(s, min(u, radius));
}

// Weight (one axis) of level-0 texel v in level-`level` texel `texel`: the blur of the mean over
// the texel's 2^level block, sum_{b in block} w(v - b) / 2^level, from the blur's cumulative
// weights. Needs a power-of-two map size whenever level > 0 (compare checks it).
PENUMBRA_INLINE float blockBlurWeight(LookupSources s, int v, int texel, int level, int radius) {
  int block = 1 << level;
  int first = texel * block;
  return (cumulativeBlur(s, v - first, radius) - cumulativeBlur(s, v - first - block, radius)) /
         float(block);
}

// A bilinear lookup at `level` (blur radius r at level 0): the tests of every level-0 texel under
// its four taps' blocks and blur, each weighted once by the separable kernel.
PENUMBRA_INLINE float referenceBilinear(LookupSources s, LookupSettings ls, int blurRadius, vec2 uv,
                                        int level, vec2 position, float receiverDepth,
                                        vec2 depthPerTexel) {
  int levelSize = mipLevelSize(ls.shadowMapSize, level);
  int block = 1 << level;
  BilinearTaps taps = bilinearTaps(uv, levelSize);
  ivec2 t0 = clampTexel(taps.base, levelSize);
  ivec2 t1 = clampTexel(taps.base + ivec2(1, 1), levelSize);
  ivec2 lo = t0 * block - ivec2(blurRadius);
  ivec2 hi = (t1 + ivec2(1, 1)) * block - ivec2(1, 1) + ivec2(blurRadius);
  float lit = 0.0f;
  for (int y = lo.y; y <= hi.y; ++y) {
    float wy = (1.0f - taps.fraction.y) * blockBlurWeight(s, y, t0.y, level, blurRadius) +
               taps.fraction.y * blockBlurWeight(s, y, t1.y, level, blurRadius);
    if (wy <= 0.0f) continue;
    for (int x = lo.x; x <= hi.x; ++x) {
      float wx = (1.0f - taps.fraction.x) * blockBlurWeight(s, x, t0.x, level, blurRadius) +
                 taps.fraction.x * blockBlurWeight(s, x, t1.x, level, blurRadius);
      if (wx <= 0.0f) continue;
      lit += wx * wy *
             referenceTexelTest(s, ls.shadowMapSize, ivec2(x, y), position, receiverDepth,
                                depthPerTexel);
    }
  }
  return lit;
}

// The summed-area lookup's box: each texel weighted by the share of it the box covers.
PENUMBRA_INLINE float referenceSummedAreaBox(LookupSources s, LookupSettings ls, SummedAreaBox box,
                                             vec2 position, float receiverDepth,
                                             vec2 depthPerTexel) {
  ivec2 lo = ivec2(floor(box.lo));
  ivec2 hi = min(ivec2(ceil(box.hi)) - ivec2(1, 1), ivec2(ls.shadowMapSize - 1));
  float area = (box.hi.x - box.lo.x) * (box.hi.y - box.lo.y);
  float lit = 0.0f;
  for (int y = lo.y; y <= hi.y; ++y) {
    float wy = intervalCoverage(y, box.lo.y, box.hi.y);
    for (int x = lo.x; x <= hi.x; ++x) {
      float w = intervalCoverage(x, box.lo.x, box.hi.x) * wy;
      if (w <= 0.0f) continue;
      lit += w * referenceTexelTest(s, ls.shadowMapSize, ivec2(x, y), position, receiverDepth,
                                    depthPerTexel);
    }
  }
  return lit / area;
}

// V_ref at uv for the lookup `ls` describes; ls.channelLevels is the number of mip levels the
// technique's lookup may use (1 without mips).
PENUMBRA_INLINE float referenceVisibility(LookupSources s, LookupSettings ls, vec2 uv,
                                          float receiverDepth, vec2 uvDx, vec2 uvDy,
                                          vec2 depthPerTexel) {
  vec2 position = uv * float(ls.shadowMapSize);
  float d = clamp(receiverDepth, 0.0f, 1.0f);
  if (ls.filterMode == kFilterSummedArea) {
    return referenceSummedAreaBox(s, ls, summedAreaBox(uv, uvDx, uvDy, ls), position, d,
                                  depthPerTexel);
  }
  int r = ls.blurRadius;
  if (ls.filterMode == kFilterPoint) {
    ivec2 texel = nearestTexel(uv, ls.shadowMapSize);
    float lit = 0.0f;
    for (int y = texel.y - r; y <= texel.y + r; ++y) {
      float wy = blockBlurWeight(s, y, texel.y, 0, r);
      for (int x = texel.x - r; x <= texel.x + r; ++x) {
        lit += blockBlurWeight(s, x, texel.x, 0, r) * wy *
               referenceTexelTest(s, ls.shadowMapSize, ivec2(x, y), position, d, depthPerTexel);
      }
    }
    return lit;
  }
  if (ls.filterMode == kFilterBilinear || ls.channelLevels == 1) {
    return referenceBilinear(s, ls, r, uv, 0, position, d, depthPerTexel);
  }
  LookupProbes probes = lookupProbes(uvDx, uvDy, ls);
  TrilinearLevels levels = trilinearLevels(probes.lod, ls.channelLevels);
  float lit = 0.0f;
  for (int k = 0; k < probes.count; ++k) {
    vec2 at = uv + probeOffset(probes, k);
    lit += (1.0f - levels.fraction) *
           referenceBilinear(s, ls, r, at, levels.level, position, d, depthPerTexel);
    if (levels.fraction > 0.0f) {
      lit += levels.fraction *
             referenceBilinear(s, ls, r, at, levels.next, position, d, depthPerTexel);
    }
  }
  return lit / float(probes.count);
}

// At most how many level-0 texel tests referenceVisibility runs for this lookup: what a GPU
// must run in one invocation (llvmpipe ends every loop of an invocation after 65535 iterations).
PENUMBRA_INLINE float referenceTexelTests(LookupSettings ls, vec2 uv, vec2 uvDx, vec2 uvDy) {
  if (ls.filterMode == kFilterSummedArea) {
    SummedAreaBox box = summedAreaBox(uv, uvDx, uvDy, ls);
    return (box.hi.x - box.lo.x + 2.0f) * (box.hi.y - box.lo.y + 2.0f);
  }
  float blur = float(2 * ls.blurRadius);
  if (ls.filterMode == kFilterPoint) return (blur + 1.0f) * (blur + 1.0f);
  if (ls.filterMode == kFilterBilinear || ls.channelLevels == 1) {
    return (blur + 2.0f) * (blur + 2.0f);
  }
  LookupProbes probes = lookupProbes(uvDx, uvDy, ls);
  TrilinearLevels levels = trilinearLevels(probes.lod, ls.channelLevels);
  float first = 2.0f * float(1 << levels.level) + blur;
  float second = levels.fraction > 0.0f ? 2.0f * float(1 << levels.next) + blur : 0.0f;
  return float(probes.count) * (first * first + second * second);
}

// Below llvmpipe's 65535 loop iterations per invocation, with room for the loops' own rows: a
// lookup whose kernel needs more texel tests is left by the camera pass to the CPU twin
// (Renderer::completeReferenceOnCpu).
const float kMaxReferenceTestsPerPixel = 48000.0f;

PENUMBRA_INLINE bool referenceLeftToCpu(LookupSettings ls, vec2 uv, vec2 uvDx, vec2 uvDy) {
  return referenceTexelTests(ls, uv, uvDx, uvDy) > kMaxReferenceTestsPerPixel;
}

PENUMBRA_END_SHARED
#endif
