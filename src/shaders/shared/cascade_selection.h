// Cascaded shadow maps, per pixel: which cascade a camera-space depth falls in, how much of the
// next cascade is blended in the blend band, and where a light-space position lands in a
// cascade's map. Shared by the camera pass and the CPU (Renderer's reference completion, tests).
//
// A cascade covers the view depths [start, end) (start = the previous cascade's end); its map is
// an orthographic box of the light's view plane, `box` = (min x, min y, size x, size y) in
// light-view units. Every cascade shares the light's depth metric (docs/cascades.md), so
// receiver depth and the technique's parameters mean the same in each.
#ifndef PENUMBRA_SHARED_CASCADE_SELECTION_H
#define PENUMBRA_SHARED_CASCADE_SELECTION_H
#include "filter_weights.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

const int kMaxCascades = 8;

// Where a cascade covering [start, end) begins to fade into the next: the last `band` of it.
PENUMBRA_INLINE float cascadeBandStart(float start, float end, float band) {
  return end - band * (end - start);
}

struct CascadeChoice {
  int index;    // the cascade whose map decides; cascade count: beyond the last (unshadowed)
  float blend;  // weight of cascade index + 1, in [0, 1): nonzero only in the blend band
};

// ends0 holds the ends of cascades 0..3, ends1 of 4..7 (view depths, increasing); `band` is the
// share of each cascade's depth range, at its far end, that fades into the next cascade (the last
// cascade fades into nothing: its far end is the shadow distance).
PENUMBRA_INLINE CascadeChoice selectCascade(float viewDepth, float start, vec4 ends0, vec4 ends1,
                                            int count, float band) {
  CascadeChoice choice;
  choice.index = count;
  choice.blend = 0.0f;
  float cascadeStart = start;
  for (int i = 0; i < count; ++i) {
    float end = i < 4 ? ends0[i] : ends1[i - 4];
    if (viewDepth < end) {
      choice.index = i;
      float bandStart = cascadeBandStart(cascadeStart, end, band);
      if (i + 1 < count && band > 0.0f && viewDepth > bandStart) {
        choice.blend = clamp((viewDepth - bandStart) / (end - bandStart), 0.0f, 1.0f);
      }
      return choice;
    }
    cascadeStart = end;
  }
  return choice;
}

// A light-view-plane position (or its derivative, with `derivative` 1) in a cascade's map's uv.
// A filter kernel kept constant in world width across cascades: `scale` is cascade 0's texel
// over this cascade's (<= 1 farther out). (2r + 1) taps scale to the nearest odd count; sigma
// scales exactly. The prefilter's blur (cascadeBlur) and PCF's kernel both follow it.
PENUMBRA_INLINE int worldConstantKernelRadius(int radius, float scale) {
  float taps = float(2 * radius + 1) * scale;
  return clamp(int(floor((taps - 1.0f) * 0.5f + 0.5f)), 0, kMaxBlurRadius);
}
PENUMBRA_INLINE float worldConstantKernelSigma(float sigma, float scale) {
  return max(0.01f, sigma * scale);
}

PENUMBRA_INLINE vec2 cascadeUv(vec2 lightPlane, vec4 box, int derivative) {
  vec2 origin = vec2(box[0], box[1]);
  vec2 size = vec2(box[2], box[3]);
  if (derivative != 0) return lightPlane / size;
  return (lightPlane - origin) / size;
}

// A depth gradient per light-view unit as a gradient per texel of a cascade's map.
PENUMBRA_INLINE vec2 cascadeDepthPerTexel(vec2 depthPerUnit, vec4 box, int shadowMapSize) {
  return depthPerUnit * vec2(box[2], box[3]) / float(shadowMapSize);
}

PENUMBRA_END_SHARED
#endif
