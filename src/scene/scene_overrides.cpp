// Camera and light overrides from the command line or a settings file, checked before use.
#include <cmath>

#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

std::string text(glm::vec3 v) {
  return std::to_string(v.x) + "," + std::to_string(v.y) + "," + std::to_string(v.z);
}

glm::vec3 checked(const std::optional<glm::vec3>& v, const char* what) {
  if (!std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z)) {
    throw Error(std::string(what) + " " + text(*v) + " is not finite");
  }
  return *v;
}

float checkedAngle(float degrees, const char* what) {
  if (!(degrees > 0.0f && degrees <= 170.0f)) {
    throw Error(std::string(what) + " " + std::to_string(degrees) +
                " degrees is out of range (0, 170]");
  }
  return degrees;
}

}  // namespace

void checkLightSize(const Light& light) {
  const bool spot = light.kind == LightKind::Spot;
  const float most = spot ? kMaxSpotLightSize : kMaxDirectionalLightSize;
  if (!(light.size >= 0.0f && light.size <= most)) {
    throw Error("light size " + std::to_string(light.size) + " is out of range [0, " +
                std::to_string(most) + "] for a " +
                (spot ? "spot light (world units of disk diameter)"
                      : "directional light (tangent of its angular diameter)"));
  }
}

bool SceneOverrides::empty() const {
  return !lightDirection && !lightPosition && !lightTarget && !spotAngleDegrees &&
         !cameraPosition && !cameraTarget && !cameraFovDegrees && !lightSize;
}

void applyOverrides(Scene& scene, const SceneOverrides& o) {
  if (o.lightDirection && o.lightPosition) {
    throw Error(
        "give a light direction (directional light) or a light position (spot light), "
        "not both");
  }
  if (o.lightDirection) {
    const glm::vec3 d = checked(o.lightDirection, "light direction");
    if (!(glm::length(d) > 1e-6f)) throw Error("light direction " + text(d) + " has no direction");
    scene.light.kind = LightKind::Directional;
    scene.light.direction = glm::normalize(d);
  }
  if ((o.lightTarget || o.spotAngleDegrees) && !o.lightPosition &&
      scene.light.kind != LightKind::Spot) {
    throw Error("a light target or spot angle needs a spot light: give a light position too");
  }
  if (o.lightPosition) {
    scene.light.kind = LightKind::Spot;
    scene.light.position = checked(o.lightPosition, "light position");
    scene.light.target =
        o.lightTarget ? checked(o.lightTarget, "light target") : scene.bounds().centre();
  } else if (o.lightTarget) {
    scene.light.target = checked(o.lightTarget, "light target");
  }
  if (o.spotAngleDegrees)
    scene.light.spotAngleDegrees = checkedAngle(*o.spotAngleDegrees, "spot angle");
  if (scene.light.kind == LightKind::Spot &&
      !(glm::length(scene.light.target - scene.light.position) > 1e-6f)) {
    throw Error("the spot light at " + text(scene.light.position) + " aims at its own position");
  }
  if (o.lightSize) scene.light.size = *o.lightSize;
  checkLightSize(scene.light);  // also a file's light, whose kind an override may have changed
  if (o.cameraPosition) scene.camera.position = checked(o.cameraPosition, "camera position");
  if (o.cameraTarget) scene.camera.target = checked(o.cameraTarget, "camera target");
  if (o.cameraFovDegrees) {
    scene.camera.verticalFovDegrees = checkedAngle(*o.cameraFovDegrees, "camera field of view");
  }
  if (!(glm::length(scene.camera.target - scene.camera.position) > 1e-6f)) {
    throw Error("the camera at " + text(scene.camera.position) + " looks at its own position");
  }
}

}  // namespace penumbra
