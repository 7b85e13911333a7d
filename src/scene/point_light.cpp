// A point light's six face views and their shared projection (shared/point_light_faces.h).
#include "penumbra/point_light.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <string>

#include "penumbra/error.h"
#include "penumbra/shared/point_light_faces.h"

namespace penumbra {

static_assert(kPointLightFaceCount == shaders::kPointLightFaces);
static_assert(kPointLightFaceCount <= kMaxCascadeCount, "the faces use the cascades' arrays");

PointLightFaces pointLightFaces(const LightView& view, glm::vec3 position, int shadowMapSize,
                                int guardTexels) {
  if (guardTexels < 0 || 2 * guardTexels >= shadowMapSize / 2) {
    throw Error("a point light's guard band of " + std::to_string(guardTexels) +
                " texels (blur radius + lookup reach + 1, plus a light size's soft width) needs "
                "shadow maps wider than " +
                std::to_string(4 * guardTexels) + " texels; this one is " +
                std::to_string(shadowMapSize) + ": use a larger shadow map or a smaller blur");
  }
  PointLightFaces faces;
  faces.guardTexels = guardTexels;
  faces.tangent = shaders::pointFaceTangent(shadowMapSize, guardTexels);
  faces.clipFromLight =
      glm::perspective(2.0f * std::atan(faces.tangent), 1.0f, view.nearDistance, view.farDistance);
  for (int f = 0; f < kPointLightFaceCount; ++f) {
    const shaders::PointFaceFrame frame = shaders::pointLightFaceFrame(f);
    // Rows right, up, -forward: the view pointFaceUv projects (glm is column-major).
    glm::mat4 m(1.0f);
    for (int c = 0; c < 3; ++c) {
      m[c][0] = frame.right[c];
      m[c][1] = frame.up[c];
      m[c][2] = -frame.forward[c];
    }
    m[3] = glm::vec4(-glm::dot(frame.right, position), -glm::dot(frame.up, position),
                     glm::dot(frame.forward, position), 1.0f);
    faces.lightFromWorld[size_t(f)] = m;
  }
  return faces;
}

CascadeFrame pointLightCascadeFrame(const LightView& view) {
  CascadeFrame frame;
  frame.light = view;
  frame.count = kPointLightFaceCount;
  frame.start = 0.0f;
  frame.ends.fill(std::numeric_limits<float>::max());
  frame.boxes.fill(glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  frame.blendBand = 0.0f;
  return frame;
}

}  // namespace penumbra
