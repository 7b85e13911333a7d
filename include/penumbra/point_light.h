// Point lights (omnidirectional shadows): six perspective faces rendered into six layers of the
// shadow-map array, each a little wider than 90 degrees (a guard band) so the per-layer prefilter
// and lookups near a face's edge read real depths. The per-receiver face choice and projection
// live in src/shaders/shared/point_light_faces.h; this builds the faces' matrices from it.
#pragma once

#include <array>
#include <glm/glm.hpp>

#include "penumbra/cascades.h"
#include "penumbra/scene.h"

namespace penumbra {

inline constexpr int kPointLightFaceCount = 6;

struct PointLightFaces {
  std::array<glm::mat4, kPointLightFaceCount> lightFromWorld{};  // face f's view (looks down -z)
  glm::mat4 clipFromLight{1.0f};  // every face's projection: 2 atan(tangent) wide, square
  float tangent = 1.0f;           // tan of the half field of view (> 1: the guard band)
  int guardTexels = 0;            // texels each side beyond the 90-degree face
};

// The faces of a point light at `position` whose depth metric `view` holds (fitLightView), for
// maps of `shadowMapSize` texels with `guardTexels` texels of guard band each side
// (pointFaceGuardTexels). Throws Error when the band leaves no face (2 guard >= size).
PointLightFaces pointLightFaces(const LightView& view, glm::vec3 position, int shadowMapSize,
                                int guardTexels);

// Six layers as a cascade frame: every face's box is its whole uv square (kernel scale 1), no
// blend band; the camera pass chooses the layer by face, not by view depth.
CascadeFrame pointLightCascadeFrame(const LightView& view);

}  // namespace penumbra
