// Scene bounds, the light's fitted view and the camera's matrices.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "penumbra/scene.h"

namespace penumbra {

namespace {

template <typename Keep>
Bounds boundsOf(const std::vector<Mesh>& meshes, Keep keep) {
  Bounds b{glm::vec3(std::numeric_limits<float>::max()),
           glm::vec3(std::numeric_limits<float>::lowest())};
  for (const Mesh& m : meshes) {
    if (!keep(m)) continue;
    for (const Vertex& v : m.vertices) {
      b.min = glm::min(b.min, v.position);
      b.max = glm::max(b.max, v.position);
    }
  }
  return b;
}

}  // namespace

namespace {

// The bounds grown by where the scene's animation takes its moving meshes (sweepClip): the
// frame's depth ranges and the light's fit hold still while the clip plays.
Bounds withSweep(Bounds b, const SceneAnimation& animation) {
  if (!(animation.sweepMin.x <= animation.sweepMax.x)) return b;
  return {glm::min(b.min, animation.sweepMin), glm::max(b.max, animation.sweepMax)};
}

}  // namespace

Bounds Scene::bounds() const {
  return withSweep(boundsOf(meshes, [](const Mesh&) { return true; }), animation);
}

Bounds Scene::modelBounds() const {
  const Bounds model = boundsOf(
      meshes, [](const Mesh& m) { return m.role == MeshRole::Model && !m.vertices.empty(); });
  return model.min.x <= model.max.x ? model : bounds();
}

Bounds Scene::shadowBounds() const {
  const Bounds shadowed = boundsOf(meshes, [](const Mesh& m) {
    return (m.castsShadow || m.role != MeshRole::Enclosure) && !m.vertices.empty();
  });
  return shadowed.min.x <= shadowed.max.x ? withSweep(shadowed, animation) : bounds();
}

std::vector<Camera> Scene::cameraPath(int frames) const {
  std::vector<Camera> path;
  for (int i = 0; i < frames; ++i) {
    const float t = frames > 1 ? float(i) / float(frames - 1) : 0.0f;
    Camera c = camera;
    c.position += t * pathOffset;
    c.target += t * pathOffset;
    path.push_back(c);
  }
  return path;
}

size_t Scene::triangleCount() const {
  size_t count = 0;
  for (const Mesh& m : meshes) count += m.indices.size() / 3;
  return count;
}

namespace {

// An up vector that is not parallel to `forward`.
glm::vec3 upFor(glm::vec3 forward) {
  return std::abs(forward.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

}  // namespace

LightView fitLightView(const Light& light, const Bounds& bounds) {
  const glm::vec3 centre = bounds.centre();
  const float radius = std::max(bounds.radius(), 1e-3f);
  LightView view;
  if (light.kind == LightKind::Directional) {
    const glm::vec3 dir = glm::normalize(light.direction);
    const glm::vec3 eye = centre - dir * (2.0f * radius);
    view.lightFromWorld = glm::lookAt(eye, centre, upFor(dir));
    view.nearDistance = radius;
    view.farDistance = 3.0f * radius;
    view.clipFromLight =
        glm::ortho(-radius, radius, -radius, radius, view.nearDistance, view.farDistance);
    view.perspective = false;
  } else if (light.kind == LightKind::Point) {
    // The faces' rotations and their projection come with the shadow map's size and guard band
    // (penumbra/point_light.h); here the translation and the range: the distance from the light
    // to the far side of the scene's bounding sphere. Near only maps depth and clips the faces:
    // casters closer to the light than a thousandth of the scene's radius cast nothing.
    const float distance = glm::length(centre - light.position);
    view.lightFromWorld = glm::translate(glm::mat4(1.0f), -light.position);
    view.nearDistance = std::max(1e-3f * radius, distance - radius);
    view.farDistance = distance + radius;
    view.clipFromLight =
        glm::perspective(glm::radians(90.0f), 1.0f, view.nearDistance, view.farDistance);
    view.perspective = true;
  } else {
    const glm::vec3 eye = light.position;
    const glm::vec3 forward = glm::normalize(light.target - eye);
    const float distance = glm::length(centre - eye);
    view.lightFromWorld = glm::lookAt(eye, light.target, upFor(forward));
    view.nearDistance = std::max(0.05f, distance - radius);
    view.farDistance = distance + radius;
    view.clipFromLight = glm::perspective(glm::radians(light.spotAngleDegrees), 1.0f,
                                          view.nearDistance, view.farDistance);
    view.perspective = true;
  }
  return view;
}

float LightView::texelWorldSize(int shadowMapSize) const {
  // clipFromLight[0][0] is 1/halfWidth (orthographic) or 1/tan(halfAngle) (perspective).
  return 2.0f / (clipFromLight[0][0] * float(shadowMapSize));
}

glm::mat4 viewFromWorld(const Camera& camera) {
  return glm::lookAt(camera.position, camera.target,
                     upFor(glm::normalize(camera.target - camera.position)));
}

float cameraFar(const Camera& camera, const ViewBounds& bounds) {
  return glm::length(bounds.drawn.centre() - camera.position) + 2.0f * bounds.drawn.radius();
}

float cameraNear(const ViewBounds& bounds) {
  // A scene smaller than the fixed floor (a model in millimetres, framed from a few of its own
  // radii) gets a tenth of its radius instead, so the floor never clips it.
  const float radius = bounds.shadowed.radius();
  return std::max(std::min(kMinCameraNear, 0.1f * radius), radius / kCameraNearPerRadius);
}

glm::mat4 clipFromView(const Camera& camera, float aspect, const ViewBounds& bounds) {
  return glm::perspective(glm::radians(camera.verticalFovDegrees), aspect, cameraNear(bounds),
                          cameraFar(camera, bounds));
}

}  // namespace penumbra
