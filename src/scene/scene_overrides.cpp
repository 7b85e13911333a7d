// Camera and light overrides from the command line or a settings file, checked before use.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

// Six significant digits: 1e+30 rather than thirty-one digits of it.
std::string text(glm::vec3 v) {
  std::ostringstream out;
  out << v.x << "," << v.y << "," << v.z;
  return out.str();
}

glm::vec3 checked(const std::optional<glm::vec3>& v, const char* what) {
  if (!std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z)) {
    throw Error(std::string(what) + " " + text(*v) + " is not finite");
  }
  const float largest = std::max({std::abs(v->x), std::abs(v->y), std::abs(v->z)});
  if (largest > kMaxWorldCoordinate) {
    throw Error(std::string(what) + " " + text(*v) + " is out of range: each coordinate within " +
                "+-1e6 world units (float positions beyond it lose the scene's detail)");
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

constexpr LightKind kLightKinds[] = {LightKind::Directional, LightKind::Spot, LightKind::Point};

}  // namespace

std::string_view lightKindName(LightKind kind) {
  switch (kind) {
    case LightKind::Directional: return "directional";
    case LightKind::Spot: return "spot";
    case LightKind::Point: return "point";
  }
  return "directional";
}

LightKind parseLightKind(std::string_view name) {
  std::string valid;
  for (LightKind k : kLightKinds) {
    if (lightKindName(k) == name) return k;
    valid += (valid.empty() ? "" : ", ") + std::string(lightKindName(k));
  }
  throw Error("unknown light kind '" + std::string(name) + "'; valid kinds: " + valid);
}

void checkLightSize(const Light& light) {
  float most = kMaxDirectionalLightSize;
  const char* what = "directional light (tangent of its angular diameter)";
  if (light.kind == LightKind::Spot) {
    most = kMaxSpotLightSize;
    what = "spot light (world units of disk diameter)";
  } else if (light.kind == LightKind::Point) {
    most = kMaxPointLightSize;
    what = "point light (world units of sphere diameter)";
  }
  if (!(light.size >= 0.0f && light.size <= most)) {
    throw Error("light size " + std::to_string(light.size) + " is out of range [0, " +
                std::to_string(most) + "] for a " + what);
  }
}

bool SceneOverrides::empty() const {
  return !lightKind && !lightDirection && !lightPosition && !lightTarget && !spotAngleDegrees &&
         !cameraPosition && !cameraTarget && !cameraFovDegrees && !lightSize;
}

void validateOverrides(const SceneOverrides& o) {
  if (o.lightDirection) {
    const glm::vec3 d = checked(o.lightDirection, "light direction");
    if (!(glm::length(d) > 1e-6f)) throw Error("light direction " + text(d) + " has no direction");
  }
  if (o.lightPosition) checked(o.lightPosition, "light position");
  if (o.lightTarget) checked(o.lightTarget, "light target");
  if (o.spotAngleDegrees) checkedAngle(*o.spotAngleDegrees, "spot angle");
  if (o.cameraPosition) checked(o.cameraPosition, "camera position");
  if (o.cameraTarget) checked(o.cameraTarget, "camera target");
  if (o.cameraFovDegrees) checkedAngle(*o.cameraFovDegrees, "camera field of view");
  // The largest size depends on the light's kind, known once the scene is loaded
  // (checkLightSize names it); what no kind takes is refused here.
  if (o.lightSize && !(*o.lightSize >= 0.0f && std::isfinite(*o.lightSize))) {
    throw Error("light size " + std::to_string(*o.lightSize) +
                " is not a size: give a finite number of at least 0");
  }
}

void applyOverrides(Scene& scene, const SceneOverrides& o) {
  validateOverrides(o);
  if (o.lightDirection && o.lightPosition) {
    throw Error(
        "give a light direction (directional light) or a light position (spot or point light), "
        "not both");
  }
  if (o.lightKind) {
    const LightKind kind = *o.lightKind;
    if (kind == LightKind::Directional && o.lightPosition) {
      throw Error("a directional light has no position: give --light-dir, or --light spot/point");
    }
    if (kind != LightKind::Directional && o.lightDirection) {
      throw Error("a " + std::string(lightKindName(kind)) +
                  " light has no direction: give --light-pos, or --light directional");
    }
    if (kind == LightKind::Point && (o.lightTarget || o.spotAngleDegrees)) {
      throw Error(
          "a point light shines every way: a light target or spot angle needs a spot light");
    }
  }
  const LightKind previous = scene.light.kind;
  if (o.lightDirection || (o.lightKind && *o.lightKind == LightKind::Directional)) {
    scene.light.kind = LightKind::Directional;
    if (o.lightDirection) {
      const glm::vec3 d = checked(o.lightDirection, "light direction");
      if (!(glm::length(d) > 1e-6f))
        throw Error("light direction " + text(d) + " has no direction");
      scene.light.direction = glm::normalize(d);
    }
  }
  const bool wantsPoint = o.lightKind && *o.lightKind == LightKind::Point;
  const bool wantsSpot =
      (o.lightKind && *o.lightKind == LightKind::Spot) || (o.lightPosition && !o.lightKind);
  if ((o.lightTarget || o.spotAngleDegrees) && !wantsSpot && scene.light.kind != LightKind::Spot) {
    throw Error("a light target or spot angle needs a spot light: give a light position too");
  }
  if (wantsSpot || wantsPoint) {
    scene.light.kind = wantsPoint ? LightKind::Point : LightKind::Spot;
    if (o.lightPosition) {
      scene.light.position = checked(o.lightPosition, "light position");
    } else if (previous == LightKind::Directional) {
      // No position given and none to keep: inside the model's bounding sphere (not an
      // enclosure's: a light outside a sky dome lights nothing), halfway from its centre
      // towards the sun the scene had, so the light keeps lighting what it lit; and above the
      // model's top by a quarter of its radius, so that it stands in no part of the model.
      const Bounds b = scene.modelBounds();
      glm::vec3 position = b.centre() - scene.light.direction * (0.5f * b.radius());
      position.y = std::max(position.y, b.max.y + 0.25f * b.radius());
      scene.light.position = position;
    }
    if (wantsSpot && (o.lightPosition || previous != LightKind::Spot)) {
      scene.light.target =
          o.lightTarget ? checked(o.lightTarget, "light target") : scene.modelBounds().centre();
    } else if (o.lightTarget) {
      scene.light.target = checked(o.lightTarget, "light target");
    }
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

SceneOverrides viewOverrides(const Scene& scene) {
  SceneOverrides o;
  const Light& light = scene.light;
  o.lightKind = light.kind;
  if (light.kind == LightKind::Directional) {
    o.lightDirection = light.direction;
  } else {
    o.lightPosition = light.position;
  }
  if (light.kind == LightKind::Spot) {
    o.lightTarget = light.target;
    o.spotAngleDegrees = light.spotAngleDegrees;
  }
  o.lightSize = light.size;
  o.cameraPosition = scene.camera.position;
  o.cameraTarget = scene.camera.target;
  o.cameraFovDegrees = scene.camera.verticalFovDegrees;
  return o;
}

}  // namespace penumbra
