// Built-in procedural scenes that recreate the papers' test cases, each with a default camera
// and light; geometry is generated in code, with normals, in world units (metres, +y up).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangles, counter-clockwise seen from outside
  glm::vec3 albedo{0.8f};
};

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  glm::vec3 centre() const { return 0.5f * (min + max); }
  float radius() const { return 0.5f * glm::length(max - min); }
};

struct Camera {
  glm::vec3 position{0.0f, 2.0f, 5.0f};
  glm::vec3 target{0.0f};
  float verticalFovDegrees = 45.0f;
};

enum class LightKind { Directional, Spot };

struct Light {
  LightKind kind = LightKind::Directional;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: the way the light travels
  glm::vec3 position{0.0f, 10.0f, 0.0f};   // spot: where it is
  glm::vec3 target{0.0f};                  // spot: where it points
  float spotAngleDegrees = 60.0f;          // spot: full cone angle
};

// A known trouble spot in the default view, in normalised image coordinates (0,0 top left).
struct TroubleSpot {
  std::string name;
  glm::vec4 rect{0.0f, 0.0f, 1.0f, 1.0f};  // x0, y0, x1, y1
};

struct Scene {
  std::string name;
  std::string description;
  std::vector<Mesh> meshes;
  Camera camera;
  Light light;
  // The camera path moves the camera by this in total: about a pixel per frame at the default
  // view, so pixels keep their surfaces and frame-to-frame change is shadow instability.
  glm::vec3 pathOffset{0.03f, 0.0f, 0.0f};
  std::vector<TroubleSpot> troubleSpots;

  // The camera path for temporal measurements: `frames` cameras from the default one to the
  // default one moved by pathOffset, the target moving alike (frame 0 is the default camera).
  std::vector<Camera> cameraPath(int frames) const;

  Bounds bounds() const;
  size_t triangleCount() const;
};

// The light's view of a scene: matrices and the linear depth metric the shadow map stores.
// Directional lights are orthographic, fitted to the scene's bounding sphere; spot lights are
// perspective over their cone. Linear depth in [0,1] is the distance along the light direction
// (directional) or from the light (spot), mapped from [near, far].
struct LightView {
  glm::mat4 lightFromWorld{1.0f};  // view
  glm::mat4 clipFromLight{1.0f};   // projection
  float nearDistance = 0.0f;
  float farDistance = 1.0f;
  bool perspective = false;
  // World-space size of one shadow-map texel at unit distance (spot) or everywhere (directional),
  // for the normal-offset bias: multiply by the distance for spot lights.
  float texelWorldSize(int shadowMapSize) const;
};

LightView fitLightView(const Light& light, const Bounds& sceneBounds);
inline LightView fitLightView(const Scene& scene) { return fitLightView(scene.light, scene.bounds()); }

// The camera's near plane and the far plane that keeps the whole scene in view.
inline constexpr float kCameraNear = 0.05f;
float cameraFar(const Camera& camera, const Bounds& sceneBounds);

// View and projection of the scene's camera for an image of the given aspect ratio.
glm::mat4 viewFromWorld(const Camera& camera);
glm::mat4 clipFromView(const Camera& camera, float aspect, const Bounds& sceneBounds);

std::span<const std::string_view> builtinSceneNames();
std::string builtinSceneNameList();
// Throws Error naming the valid scenes when the name is unknown.
Scene makeBuiltinScene(std::string_view name);

}  // namespace penumbra
