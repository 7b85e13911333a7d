// The filtered reference (docs/reference.md): the exact PCF of the raw depth map under the same
// effective kernel a technique's prefilter and lookup apply — the blur kernel at level 0,
// averaged over each mip texel's block, weighted by the hardware lookup's taps — with every tap
// tested against the receiver's plane extended to that texel.
#ifndef PENUMBRA_LIB_FILTERED_REFERENCE_GLSL
#define PENUMBRA_LIB_FILTERED_REFERENCE_GLSL
#include "shadow_lookup.glsl"

layout(binding = 2) uniform sampler2D rawDepth;
const int kMaxReferenceBlur = 64;
uniform float referenceBlurWeights[2 * kMaxReferenceBlur + 1];
uniform int referenceBlurRadius;
uniform int referenceLevels;  // mip levels the technique's lookup may use

// Ties within this count as lit: the receiver plane extended to a texel reproduces that texel's
// stored depth only to rounding.
const float kReferenceTie = 2.0e-5f;
// A mip texel's block is sampled on a grid of at most this many texels per side.
const int kMaxBlockSide = 8;

// Blurred shadow test of level-0 texel t for a receiver plane through `position` (level-0 texels).
float blurredTest(ivec2 t, vec2 position, float receiverDepth, vec2 depthPerTexel) {
  float lit = 0.0f;
  int size = shadowMapSize;
  for (int j = -referenceBlurRadius; j <= referenceBlurRadius; ++j) {
    for (int i = -referenceBlurRadius; i <= referenceBlurRadius; ++i) {
      ivec2 q = clamp(t + ivec2(i, j), ivec2(0), ivec2(size - 1));
      float z = texelFetch(rawDepth, q, 0).x;
      float d = receiverDepth + dot(depthPerTexel, vec2(t + ivec2(i, j)) + 0.5f - position);
      float w = referenceBlurWeights[i + referenceBlurRadius] * referenceBlurWeights[j + referenceBlurRadius];
      lit += w * (z >= d - kReferenceTie ? 1.0f : 0.0f);
    }
  }
  return lit;
}

// A level-L texel: the mean of its 2^L x 2^L block of blurred level-0 tests.
float referenceTexel(int level, ivec2 texel, vec2 position, float receiverDepth, vec2 depthPerTexel) {
  int block = 1 << level;
  int stride = max(1, block / kMaxBlockSide);
  int count = 0;
  float lit = 0.0f;
  for (int by = 0; by < block; by += stride) {
    for (int bx = 0; bx < block; bx += stride) {
      lit += blurredTest(texel * block + ivec2(bx, by) + (stride - 1) / 2, position, receiverDepth, depthPerTexel);
      ++count;
    }
  }
  return lit / float(count);
}

float referenceBilinear(vec2 uv, int level, vec2 position, float receiverDepth, vec2 depthPerTexel) {
  int size = max(shadowMapSize >> level, 1);
  vec2 p = uv * float(size) - 0.5f;
  ivec2 base = ivec2(floor(p));
  vec2 f = p - vec2(base);
  float lit = 0.0f;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      float w = (i == 0 ? 1.0f - f.x : f.x) * (j == 0 ? 1.0f - f.y : f.y);
      if (w <= 0.0f) continue;
      ivec2 texel = clamp(base + ivec2(i, j), ivec2(0), ivec2(size - 1));
      lit += w * referenceTexel(level, texel, position, receiverDepth, depthPerTexel);
    }
  }
  return lit;
}

float referenceTrilinear(vec2 uv, float lod, vec2 position, float receiverDepth, vec2 depthPerTexel) {
  lod = clamp(lod, 0.0f, float(referenceLevels - 1));
  int level = int(floor(lod));
  float t = lod - float(level);
  float lit = (1.0f - t) * referenceBilinear(uv, level, position, receiverDepth, depthPerTexel);
  if (t > 0.0f) {
    lit += t * referenceBilinear(uv, min(level + 1, referenceLevels - 1), position, receiverDepth, depthPerTexel);
  }
  return lit;
}

float referenceVisibility(vec2 uv, float receiverDepth, vec2 uvDx, vec2 uvDy, vec2 depthPerTexel) {
  vec2 position = uv * float(shadowMapSize);
  if (filterMode == kFilterPoint) {
    ivec2 texel = clamp(ivec2(floor(position)), ivec2(0), ivec2(shadowMapSize - 1));
    return blurredTest(texel, position, receiverDepth, depthPerTexel);
  }
  if (filterMode == kFilterSummedArea) {
    vec2 footprint = max(abs(uvDx), abs(uvDy)) * float(shadowMapSize);
    int radius = max(satMinRadius, int(ceil(0.5f * max(footprint.x, footprint.y) - 0.5f)));
    ivec2 centre = clamp(ivec2(floor(position)), ivec2(0), ivec2(shadowMapSize - 1));
    ivec2 lo = clamp(centre - radius, ivec2(0), ivec2(shadowMapSize - 1));
    ivec2 hi = clamp(centre + radius, ivec2(0), ivec2(shadowMapSize - 1));
    int stride = max(1, (hi.x - lo.x + 1) / (4 * kMaxBlockSide));
    float lit = 0.0f;
    int count = 0;
    for (int y = lo.y; y <= hi.y; y += stride) {
      for (int x = lo.x; x <= hi.x; x += stride) {
        float z = texelFetch(rawDepth, ivec2(x, y), 0).x;
        float d = receiverDepth + dot(depthPerTexel, vec2(x, y) + 0.5f - position);
        lit += z >= d - kReferenceTie ? 1.0f : 0.0f;
        ++count;
      }
    }
    return lit / float(count);
  }
  if (filterMode == kFilterBilinear || referenceLevels == 1) {
    return referenceBilinear(uv, 0, position, receiverDepth, depthPerTexel);
  }
  // Trilinear, and anisotropic as probes along the footprint's major axis (the hardware's exact
  // anisotropic kernel is the driver's own; this is the usual model of it).
  vec2 dx = uvDx * float(shadowMapSize);
  vec2 dy = uvDy * float(shadowMapSize);
  float major = max(max(length(dx), length(dy)), 1e-6f);
  float minor = max(min(length(dx), length(dy)), 1e-6f);
  int probes = filterMode == kFilterAnisotropic ? clamp(int(ceil(major / minor)), 1, anisotropy) : 1;
  float lod = log2(major / float(probes));
  vec2 axis = length(dx) >= length(dy) ? uvDx : uvDy;
  float lit = 0.0f;
  for (int k = 0; k < probes; ++k) {
    vec2 offset = axis * ((float(k) + 0.5f) / float(probes) - 0.5f);
    lit += referenceTrilinear(uv + offset, lod, position, receiverDepth, depthPerTexel);
  }
  return lit / float(probes);
}

#endif
