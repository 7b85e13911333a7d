// Soft shadows from a disk light (Light::size), written once for the GPU and the CPU twin:
// PCSS's blocker search and penumbra estimate (Fernando, "Percentage-Closer Soft Shadows", 2005),
// driving PCF's variable kernel and the filterable techniques' variable filter width (mip level
// or summed-area box, docs/techniques.md "Soft shadows").
#ifndef PENUMBRA_SHARED_SOFT_SHADOW_H
#define PENUMBRA_SHARED_SOFT_SHADOW_H
#include "filter_weights.h"
#include "hard.h"
#include "light_depth.h"
#include "lookup_access.h"
#include "lookup_footprint.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// The light as the lookup sees it. Linear depth d in [0,1] is the distance
// near + d (far - near): from the light (spot, point) or along its direction (directional).
struct SoftLight {
  float size;          // 0: hard. Spot: disk diameter, world units; point: sphere diameter, world
                       // units, taken as the disk of that diameter facing the receiver
                       // (docs/techniques.md "Soft shadows"); directional: the tangent of the
                       // angular diameter (penumbra per unit of distance)
  int perspective;     // 1: spot light or a point light's face, 0: directional
  float nearDistance;  // world units
  float farDistance;
  float texelWorldSize;  // a level-0 texel's world size: directional everywhere, spot and point
                         // faces at unit distance (LightView::texelWorldSize)
  float maxWidthTexels;  // the widest blocker search and filter: kMaxSoftWidthTexels, a point
                         // light's pointLightSoftWidthTexels (its faces' guard band holds it)
};

// Taps per side of the blocker search and of PCSS's kernel: fixed counts, spread over a width
// that varies, so the cost is the same for any light size (64 depth reads; 64 bilinear tests).
const int kBlockerSearchSide = 8;
const int kPcssSide = 8;
// The widest blocker search and filter, in level-0 texels: the search stays local and the
// summed-area and mip lookups stay within the map's scale.
const float kMaxSoftWidthTexels = 128.0f;

// A point light's widest blocker search and filter: a sixteenth of the map, at most
// kMaxSoftWidthTexels. Every tap of a lookup at a face's 90-degree edge lies within one width of
// it (see pointFaceGuardTexels), so the faces' guard band grows by this many texels: 16 of 256,
// 64 of 1024, keeping 7/8 of each face's texels on its 90 degrees (docs/techniques.md).
PENUMBRA_INLINE float pointLightSoftWidthTexels(int shadowMapSize) {
  return min(kMaxSoftWidthTexels, float(shadowMapSize / 16));
}
// A blocker lies in front of the receiver plane extended to its texel by more than this (linear
// depth): the hard test's default constant bias, which absorbs the plane's fp32 rounding over a
// wide search.
const float kBlockerTolerance = 0.0005f;

PENUMBRA_INLINE float softLightDistance(SoftLight l, float depth) {
  return lightDistanceAtDepth(depth, l.nearDistance, l.farDistance);
}

// World size of a level-0 texel at linear depth `depth` (spot: at that distance, on the plane
// perpendicular to the axis; off-axis texels are larger by up to 1/cos of the half cone angle).
PENUMBRA_INLINE float softTexelWorldSize(SoftLight l, float depth) {
  return l.perspective != 0 ? l.texelWorldSize * softLightDistance(l, depth) : l.texelWorldSize;
}

// Penumbra width on the receiver, in world units, from similar triangles (Fernando 2005, eq. 1):
// spot, a disk of diameter S at distance 0: w = S (z_r - z_b) / z_b. Directional, the same with
// the light at distance D -> infinity and S / D kept as the angular size s: w = s (z_r - z_b).
PENUMBRA_INLINE float penumbraWorldWidth(SoftLight l, float receiverDepth, float blockerDepth) {
  float receiver = softLightDistance(l, receiverDepth);
  float blocker = softLightDistance(l, blockerDepth);
  float spread = max(receiver - blocker, 0.0f);
  return l.perspective != 0 ? l.size * spread / max(blocker, 1.0e-6f) : l.size * spread;
}

// The penumbra width in level-0 texels around the receiver's lookup. With the blocker at depth 0
// (the light's near plane, fitted to the scene's bounds, so no blocker is nearer) it is also the
// blocker search's width: the cross-section of the cone from the receiver to the light disk, in
// texels at any depth d, is S (z_r - z) / (z_r z texel) (spot) or s (z_r - z) / texel
// (directional), widest at the near plane (Fernando's search region).
PENUMBRA_INLINE float penumbraTexels(SoftLight l, float receiverDepth, float blockerDepth) {
  // w is measured at the receiver, where the map's texels are softTexelWorldSize wide.
  return penumbraWorldWidth(l, receiverDepth, blockerDepth) /
         max(softTexelWorldSize(l, receiverDepth), 1.0e-12f);
}

struct BlockerEstimate {
  float depth;  // mean linear depth of the blockers found (1 when none)
  float share;  // share of the search taps that found a blocker, in [0,1]
};

// Step 1 of PCSS: the mean depth of the texels in the search region that lie in front of the
// receiver plane (depthPerTexel: its depth gradient per texel), on a regular grid of taps.
PENUMBRA_INLINE BlockerEstimate searchBlockers(LookupSources s, int size, SoftLight l, vec2 uv,
                                               float receiverDepth, vec2 depthPerTexel) {
  float width = clamp(penumbraTexels(l, receiverDepth, 0.0f), 1.0f, l.maxWidthTexels);
  vec2 centre = uv * float(size);
  float sum = 0.0f;
  float count = 0.0f;
  for (int j = 0; j < kBlockerSearchSide; ++j) {
    for (int i = 0; i < kBlockerSearchSide; ++i) {
      vec2 grid = (vec2(float(i), float(j)) + 0.5f) / float(kBlockerSearchSide) - 0.5f;
      ivec2 texel = clampTexel(ivec2(floor(centre + grid * width)), size);
      float z = lightDepthTexel(s, texel);
      float plane = receiverDepth + dot(depthPerTexel, vec2(texel) + 0.5f - centre);
      if (z < plane - kBlockerTolerance) {
        sum += z;
        count += 1.0f;
      }
    }
  }
  BlockerEstimate b;
  b.depth = count > 0.0f ? sum / count : 1.0f;
  b.share = count / float(kBlockerSearchSide * kBlockerSearchSide);
  return b;
}

// Step 2: the filter width in texels for the blockers found, in [0, l.maxWidthTexels].
PENUMBRA_INLINE float softFilterTexels(SoftLight l, float receiverDepth, BlockerEstimate b) {
  return clamp(penumbraTexels(l, receiverDepth, b.depth), 0.0f, l.maxWidthTexels);
}

// Step 3 for PCF: a box of `width` texels (at least one) sampled by kPcssSide^2 bilinear depth
// tests, each against the receiver plane at its position: the box convolved with the bilinear
// tent, so the kernel moves and grows smoothly. `bias` is PCF's (slope-scaled by the plane).
PENUMBRA_INLINE float pcssVisibility(LookupSources s, int size, vec2 uv, float receiverDepth,
                                     vec2 depthPerTexel, int receiverPlane, HardParams bias,
                                     float width) {
  vec2 centre = uv * float(size);
  float span = max(width, 1.0f);
  float slope = abs(depthPerTexel.x) + abs(depthPerTexel.y);
  float lit = 0.0f;
  for (int j = 0; j < kPcssSide; ++j) {
    for (int i = 0; i < kPcssSide; ++i) {
      vec2 at = centre + ((vec2(float(i), float(j)) + 0.5f) / float(kPcssSide) - 0.5f) * span;
      BilinearTaps taps = bilinearTaps(at / float(size), size);
      for (int b = 0; b < 2; ++b) {
        for (int a = 0; a < 2; ++a) {
          float w = bilinearTapWeight(taps, a, b);
          if (w <= 0.0f) continue;
          ivec2 texel = taps.base + ivec2(a, b);
          float z = lightDepthTexel(s, clampTexel(texel, size));
          float d = receiverDepth;
          if (receiverPlane != 0) d += dot(depthPerTexel, vec2(texel) + 0.5f - centre);
          lit += w * hardVisibility(z, biasedReceiverDepth(d, slope, bias));
        }
      }
    }
  }
  return clamp(lit / float(kPcssSide * kPcssSide), 0.0f, 1.0f);
}

// Step 3 for the filterable techniques: the lookup's footprint widened to the filter width
// (square, where the pixel's own footprint is narrower), so
// the filter mode's own machinery filters over it: the summed-area box takes the width as is
// (a box of `width` texels); a mip-mapped lookup at lod log2(f) averages 2^lod-texel blocks
// bilinearly, whose kernel (block x tent) has the variance of a box of sqrt(3) f, so it gets
// f = width / sqrt(3): the same second moment as PCSS's box.
struct SoftFootprint {
  vec2 uvDx;
  vec2 uvDy;
};

PENUMBRA_INLINE SoftFootprint softFootprint(vec2 uvDx, vec2 uvDy, float width, int size,
                                            int filterMode) {
  float texels = filterMode == kFilterSummedArea ? width : width * 0.57735027f;
  float least = texels / float(size);
  SoftFootprint f;
  f.uvDx = uvDx;
  f.uvDy = uvDy;
  // A footprint wider than the penumbra already filters more than it asks (minification).
  if (max(max(abs(uvDx.x), abs(uvDx.y)), max(abs(uvDy.x), abs(uvDy.y))) < least) {
    f.uvDx = vec2(least, 0.0f);
    f.uvDy = vec2(0.0f, least);
  }
  return f;
}

// The part of a penumbra of `width` texels the mip probes still have to filter once the
// prefilter's blur has: widths of box kernels combine like standard deviations, so the probes'
// box gets the variance width^2 / 12 less the blur's (box of 2r+1 taps: r (r + 1) / 3; Gaussian:
// sigma^2, its truncation ignored). Without this the blur and the penumbra's filter stacked: on
// backyard the default 5-tap blur widened every soft filterable technique's penumbra beyond the
// area light's.
PENUMBRA_INLINE float softWidthBeyondBlur(float width, LookupSettings ls) {
  float r = float(ls.blurRadius);
  float blurVariance =
      ls.blurKernel == kKernelGaussian ? ls.blurSigma * ls.blurSigma : r * (r + 1.0f) / 3.0f;
  return sqrt(max(width * width - 12.0f * blurVariance, 0.0f));
}

// Mip-mapped soft lookups probe the box of `width` texels at kSoftProbeSide^2 points, each probe
// filtered over width / kSoftProbeSide (softFootprint), the probes combined by each channel's
// reduction (shadow_lookup.h softFilterChannels): like PCSS's taps, shifted kernels that tile the
// box, so the kernel is centred on the lookup and grows smoothly instead of following the mip
// chain's block grid (one probe at the box's level showed its blocks in wide penumbrae). The
// grid's variance plus a probe's equals the box's (2^lod = width / (K sqrt 3) per probe).
const int kSoftProbeSide = 4;

PENUMBRA_INLINE vec2 softProbeOffset(int i, int j, float width, int size) {
  return ((vec2(float(i), float(j)) + 0.5f) / float(kSoftProbeSide) - 0.5f) * (width / float(size));
}

PENUMBRA_END_SHARED
#endif
