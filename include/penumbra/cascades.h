// Cascaded shadow maps for directional lights: split the camera's depth range, fit one
// orthographic map per split, optionally stabilised against shimmering (docs/cascades.md).
// The per-pixel selection and blend live in src/shaders/shared/cascade_selection.h.
#pragma once

#include <array>
#include <string_view>
#include <glm/glm.hpp>
#include <vector>

#include "penumbra/filters.h"
#include "penumbra/scene.h"

namespace penumbra {

inline constexpr int kMaxCascadeCount = 8;
// At most half of a cascade blends into the next: beyond it a pixel would blend past the next
// cascade's own blend band.
inline constexpr float kMaxCascadeBlendBand = 0.5f;

enum class CascadeFit {
  Tight,       // the light-view bounding box of the split's frustum corners: sharpest, shimmers
  Stabilized,  // bounding sphere of the split (rotation-invariant size) snapped to whole texels
};

// "stabilized" or "tight"; parseCascadeFit throws Error listing the valid names.
std::string_view cascadeFitName(CascadeFit fit);
CascadeFit parseCascadeFit(std::string_view name);

struct CascadeSettings {
  int count = 1;  // [1, 8]; 1: one shadow map fitted to the whole scene (any light type)
  // Practical split scheme (Zhang et al. 2006, PSSM): each split mixes the logarithmic and the
  // uniform split by lambda in [0, 1]; 0.5 is the PSSM paper's and Babylon.js's default.
  float lambda = 0.5f;
  // Given split distances (view depth, world units): count - 1 increasing values strictly inside
  // the shadow range; empty: the practical scheme.
  std::vector<float> distances;
  // Split the depth range the camera actually sees (min/max of its depth buffer, reduced on the
  // GPU; sample-distribution shadow maps, Lauritzen et al. 2011) instead of [near, max distance].
  bool fitDepthBounds = false;
  CascadeFit fit = CascadeFit::Stabilized;
  // Share of each cascade's depth range, at its far end, blended with the next cascade:
  // [0, kMaxCascadeBlendBand].
  float blendBand = 0.1f;
  // Shadows end here (view depth, world units); 0: defaultShadowDistance.
  float maxDistance = 0.0f;
};

// The shadow distance when none is set: the distance from the camera to the far side of the
// bounding sphere of what takes part in shadows (Scene::shadowBounds: not a sky dome), rounded up
// to whole diameters, so that it covers them from wherever the camera is and stays constant while
// the camera moves within a shell (stabilised cascades keep their sizes).
float defaultShadowDistance(const Camera& camera, const Bounds& shadowBounds);

// Throws Error naming the setting and its range.
void validateCascadeSettings(const CascadeSettings& settings);
// Cascades split a directional light's view; throws Error (naming --cascades) for more than one
// cascade with any other light.
void requireCascadableLight(const CascadeSettings& settings, const Light& light);

// The view depths where cascades 0..count-1 end, by the practical scheme (PSSM eq. 7-9):
// lambda * near * (far/near)^(i/count) + (1 - lambda) * (near + (far - near) * i/count).
std::vector<float> practicalSplitEnds(float near, float far, int count, float lambda);

// One frame's cascades: the shared light view (rotation and depth metric of fitLightView) and,
// per cascade, its depth range end and its map's box on the light's view plane.
struct CascadeFrame {
  LightView light;  // lightFromWorld and the depth metric shared by every cascade
  int count = 1;
  float start = 0.0f;                       // view depth where cascade 0 begins
  std::array<float, kMaxCascadeCount> ends{};  // view depth where cascade i ends
  std::array<glm::vec4, kMaxCascadeCount> boxes{};  // (min x, min y, size x, size y), light view
  float blendBand = 0.0f;

  // The orthographic projection of cascade i over the shared depth metric.
  glm::mat4 clipFromLight(int cascade) const;
  // World size of one texel of cascade i's map (its larger axis).
  float texelWorldSize(int cascade, int shadowMapSize) const;
  // Cascade 0's texel over cascade i's: how filter kernels scale to keep their world width.
  float kernelScale(int cascade, int shadowMapSize) const {
    return texelWorldSize(0, shadowMapSize) / texelWorldSize(cascade, shadowMapSize);
  }
};

// A camera depth range: the near plane (where cascade 0 begins) and, with fitted depth bounds,
// the visible [nearest, farthest] view depth that narrows the shadow distance.
struct DepthRange {
  float near = 0.05f;
  float far = 1.0f;
};

// Fits `settings.count` cascades for a directional light over the camera's view from range.near
// to the shadow distance: splits by the settings, then per split a tight or a stabilised box.
CascadeFrame fitCascades(const CascadeSettings& settings, const Camera& camera, float aspect,
                         DepthRange range, const Light& light, const Bounds& shadowBounds,
                         int shadowMapSize);

// The prefilter kernel of a cascade given cascade 0's and `scale` = cascade 0's texel over this
// cascade's (CascadeFrame::kernelScale): the same world-space width, (2r + 1) texels rounded to
// the nearest odd count, and sigma scaled exactly (shared/cascade_selection.h).
BlurSpec cascadeBlur(const BlurSpec& nearest, float scale);

}  // namespace penumbra
