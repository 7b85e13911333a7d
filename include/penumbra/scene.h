// Scenes: the built-in procedural ones that recreate the papers' test cases and scenes loaded
// from glTF 2.0 and OBJ files, each with a camera and a light; geometry with normals, texture
// coordinates and materials, in world units (metres, +y up).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/scene_animation.h"

namespace penumbra {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;  // unit length
  // glTF's convention: (0,0) is the texture image's first (top) row's first texel.
  glm::vec2 texcoord{0.0f};
};

// An RGBA8 image, row 0 at the top: colour in sRGB, alpha linear (glTF 2.0 §3.9.2).
struct TextureImage {
  std::string name;  // where it came from, for messages
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
};

// What a mesh is to the scene. A loaded file's meshes are Model; loadScene marks geometry that
// encloses the rest (a sky dome, a skybox) as Enclosure and adds a Ground under a lone model
// (SceneLoadOptions). Framing and the default lights look at the Model meshes only.
enum class MeshRole { Model, Enclosure, Ground };

// How a material's alpha (texture alpha x factor alpha) decides coverage. The light and camera
// passes test Mask against alphaCutoff. Blend lets 1 - alpha of the light through: the light pass
// covers a dithered alpha share of the shadow map's texels, which filtering averages
// (shared/alpha_mask.h), the ray-traced truth attenuates its shadow rays by 1 - alpha; the
// camera sees it as a mask at 0.5.
enum class AlphaMode { Opaque, Mask, Blend };

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangles, counter-clockwise seen from outside
  glm::vec3 albedo{0.8f};         // base-colour factor, linear RGB
  float opacity = 1.0f;           // base-colour factor's alpha
  int baseColorTexture = -1;      // index into Scene::textures (multiplies albedo and opacity)
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // Mask: covered where alpha >= alphaCutoff
  // Single-sided meshes are culled from behind in the camera pass (glTF's doubleSided: false);
  // every mesh casts shadows from both sides.
  bool doubleSided = true;
  MeshRole role = MeshRole::Model;
  // glTF's KHR_materials_unlit: an emissive backdrop, not a surface that blocks light.
  bool unlit = false;
  // Drawn in the light pass and blocking the ray-traced truth's shadow rays. loadScene clears it
  // for enclosures and unlit materials unless SceneLoadOptions::casters is All.
  bool castsShadow = true;

  bool alphaTested() const { return alphaMode != AlphaMode::Opaque; }
  float effectiveAlphaCutoff() const { return alphaMode == AlphaMode::Blend ? 0.5f : alphaCutoff; }
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

// Point: omnidirectional, six perspective faces (penumbra/point_light.h, docs/renderer.md).
enum class LightKind { Directional, Spot, Point };

// "directional", "spot", "point"; parseLightKind throws Error listing the valid names.
std::string_view lightKindName(LightKind kind);
LightKind parseLightKind(std::string_view name);

struct Light {
  LightKind kind = LightKind::Directional;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: the way the light travels
  glm::vec3 position{0.0f, 10.0f, 0.0f};   // spot and point: where it is
  glm::vec3 target{0.0f};                  // spot: where it points
  float spotAngleDegrees = 60.0f;          // spot: full cone angle
  // Soft shadows (docs/reference.md, area light): 0 is an ideal point light (hard shadows).
  // Spot: the diameter in world units of a disk light at `position` facing along the spot axis,
  // [0, 10]. Point: the diameter in world units of a sphere at `position`, [0, 10] (the renderer
  // refuses sizes above 0 for now: hard point-light shadows only).
  // Directional: the tangent of the sun disk's angular diameter, i.e. world units of disk
  // diameter per world unit of distance, [0, 0.5] (the sun's is 0.0093): a light at infinity has
  // no size in world units, only this ratio, which is what its penumbra depends on.
  float size = 0.0f;
};

// The largest light size of each kind (Light::size).
inline constexpr float kMaxSpotLightSize = 10.0f;
inline constexpr float kMaxDirectionalLightSize = 0.5f;
inline constexpr float kMaxPointLightSize = 10.0f;

// The largest coordinate a camera or light vector, a shadow distance or a cascade split may
// have, in world units. Views and light matrices are built in float (24-bit significand): at 1e6
// one float step is 1/16 of a unit, so farther positions snap by more than a scene's small
// details, and squared lengths (up to 3e12) stay far inside float's range, where 1e30 squared
// overflows to infinity and a direction normalises to zero (an empty frame).
inline constexpr float kMaxWorldCoordinate = 1e6f;

// Throws Error naming the valid range when the light's size is not finite or out of range.
void checkLightSize(const Light& light);

// A known trouble spot in the default view, in normalised image coordinates (0,0 top left).
struct TroubleSpot {
  std::string name;
  glm::vec4 rect{0.0f, 0.0f, 1.0f, 1.0f};  // x0, y0, x1, y1
};

// The extents a frame's depth ranges come from (Scene::viewBounds). The camera's far plane
// reaches past everything drawn; its near plane, the light's fit and the cascades' shadow
// distance come from what takes part in shadows, so that a sky dome a thousand times the model's
// size moves neither the near plane into the model nor the light's map off it (receivers outside
// the map read as lit: nothing there casts).
struct ViewBounds {
  Bounds drawn;     // every mesh (Scene::bounds)
  Bounds shadowed;  // casters and the model and ground that receive (Scene::shadowBounds)
};

// A camera a scene file defines, with the name it gives it (may be empty).
struct NamedCamera {
  std::string name;
  Camera camera;
};

struct Scene {
  std::string name;
  std::string description;
  std::vector<Mesh> meshes;
  std::vector<TextureImage> textures;  // referenced by Mesh::baseColorTexture
  Camera camera;
  Light light;
  // The camera path moves the camera by this in total: about a pixel per frame at the default
  // view, so pixels keep their surfaces and frame-to-frame change is shadow instability.
  glm::vec3 pathOffset{0.03f, 0.0f, 0.0f};
  std::vector<TroubleSpot> troubleSpots;  // none known for scenes from files
  // A glTF file's perspective cameras in the order its scene's nodes place them (--camera N).
  std::vector<NamedCamera> fileCameras;
  // What a loader accepted with a caveat (a texture that failed to load, BLEND as a mask, ...),
  // for the front ends to print.
  std::vector<std::string> warnings;
  // What a loader decided for the user that they may want to undo (a ground added, enclosures
  // left out of the shadows), with the option that undoes it, for the front ends to print.
  std::vector<std::string> notes;
  // A glTF file's node animation and skins (penumbra/scene_animation.h); the meshes hold the pose
  // at the clip's start (poseScene places them at any other time).
  SceneAnimation animation;

  // The camera path for temporal measurements: `frames` cameras from the default one to the
  // default one moved by pathOffset, the target moving alike (frame 0 is the default camera).
  std::vector<Camera> cameraPath(int frames) const;

  // Every mesh, and where the animation takes the moving ones over its clip (sweepClip).
  Bounds bounds() const;
  // The bounds of the Model meshes (MeshRole): what framing and the default lights look at;
  // bounds() where the scene has none.
  Bounds modelBounds() const;
  // The bounds of every mesh but enclosures that cast no shadow: every caster, and the model and
  // ground that receive their shadows; bounds() where the scene has none.
  Bounds shadowBounds() const;
  ViewBounds viewBounds() const { return {bounds(), shadowBounds()}; }
  size_t triangleCount() const;
};

// The light's view of a scene: matrices and the linear depth metric the shadow map stores.
// `shadowBounds` holds every caster and the receivers that matter (Scene::shadowBounds).
// Directional lights are orthographic, fitted to their bounding sphere; spot lights are
// perspective over their cone; point lights are a translation to the light (each face's rotation
// and projection: penumbra/point_light.h) with a range reaching the far side of their bounding
// sphere. Linear depth in [0,1] is the distance along the light direction
// (directional) or from the light (spot, point), mapped from [near, far].
struct LightView {
  glm::mat4 lightFromWorld{1.0f};  // view
  glm::mat4 clipFromLight{1.0f};   // projection
  float nearDistance = 0.0f;
  float farDistance = 1.0f;
  bool perspective = false;
  // World-space size of one shadow-map texel at unit distance (spot, a point light's faces) or
  // everywhere (directional), for the normal-offset bias: multiply by the distance for spot and
  // point lights.
  float texelWorldSize(int shadowMapSize) const;
};

LightView fitLightView(const Light& light, const Bounds& shadowBounds);
inline LightView fitLightView(const Scene& scene) {
  return fitLightView(scene.light, scene.shadowBounds());
}

// The far plane that keeps everything drawn in view (ViewBounds::drawn), and the near plane: the
// bounding radius of what takes part in shadows (ViewBounds::shadowed, the model without its sky
// dome) / kCameraNearPerRadius, but no nearer than kMinCameraNear (or a tenth of the radius for a
// scene smaller than half a unit, which the framing camera sees from a few radii) — the scene's,
// not the camera's, so that it holds still while the camera moves (cascade splits start at it). A
// fp32 depth buffer resolves view depth z to about ulp(1) z / near relative: 1.5e-4 of z at the
// far plane of a camera framing the scene from 3 radii, 1e-3 only from 30 radii, whatever the
// scene's scale (a fixed 0.05 left 2CylinderEngine, framed from 900 units, resolved to 1e-3).
inline constexpr float kMinCameraNear = 0.05f;
inline constexpr float kCameraNearPerRadius = 500.0f;
float cameraFar(const Camera& camera, const ViewBounds& bounds);
float cameraNear(const ViewBounds& bounds);

// View and projection of the scene's camera for an image of the given aspect ratio.
glm::mat4 viewFromWorld(const Camera& camera);
glm::mat4 clipFromView(const Camera& camera, float aspect, const ViewBounds& bounds);

std::span<const std::string_view> builtinSceneNames();
std::string builtinSceneNameList();
// Throws Error naming the valid scenes when the name is unknown.
Scene makeBuiltinScene(std::string_view name);

// Scene files are untrusted input: a few hundred kilobytes can describe gigabytes of geometry or
// texels, or a hierarchy deep enough to exhaust a recursive walk. These bound what a file may
// cost to load (docs/untrusted-input.md).
//
// The deepest glTF node hierarchy loaded, in levels (a root is level 1). Real models nest fewer
// than 50 levels (a skeleton's joints, an assembly's parts); this is twenty times that. The walk
// keeps a transform per level on the heap, not on the thread's stack, but a hierarchy this deep
// is a hostile or broken file, not a model.
inline constexpr int kMaxGltfNodeDepth = 1024;

// The range of SceneLoadOptions::maxMemoryBytes: 1 MiB to 1 PiB.
inline constexpr uint64_t kMinSceneMemoryBytes = uint64_t(1) << 20;
inline constexpr uint64_t kMaxSceneMemoryBytes = uint64_t(1) << 50;

// Half this machine's physical memory (sysconf), within the range above; 4 GiB where the machine
// does not say. The GL renderer's budget on a GL that does not report its memory is the other
// half.
uint64_t defaultSceneMemoryLimit();

// --ground: Auto adds a ground plane under a scene file's model when no large upward-facing
// surface lies at the bottom of its bounds; On always, Off never.
enum class GroundMode { Auto, On, Off };
// --casters: Auto leaves enclosures and unlit materials out of the shadows; All keeps every mesh.
enum class CasterMode { Auto, All };

// "auto", "on", "off" / "auto", "all"; the parsers throw Error listing the valid names.
std::string_view groundModeName(GroundMode mode);
GroundMode parseGroundMode(std::string_view name);
std::string_view casterModeName(CasterMode mode);
CasterMode parseCasterMode(std::string_view name);
// A --camera index as written ("0", "12"), or nothing for text that is not a whole number (the
// front ends say what they take); loadScene checks it against the file's cameras.
std::optional<int> parseCameraIndex(std::string_view text);

// The default camera of a scene file: it looks at the centre of the model's bounds
// (Scene::modelBounds) from the front (+z), above, along kFramingDirection, with a 45-degree
// vertical field of view, from the distance at which the model's vertices span kFramingFill of
// the frame's width or height from its centre (whichever binds first) at the frame's aspect
// (width / height).
inline constexpr float kFramingFill = 0.8f;
inline constexpr glm::vec3 kFramingDirection{0.45f, 0.55f, 1.0f};  // from the model to the camera
Camera framingCamera(const Scene& scene, float aspect);

// What a camera sees of a scene's model at an aspect: the share of the Model meshes' surface
// area whose triangles lie wholly in its view (all three corners), and the share of the frame their
// bounding box's projection covers (clipped to the frame).
struct CameraSight {
  float surfaceShare = 0.0f;
  float frameShare = 0.0f;
};
CameraSight cameraSight(const Scene& scene, const Camera& camera, float aspect);
// A file's camera is the default only when it sees the whole model: all but a thousandth of its
// surface (a camera that crops the model at the frame's aspect is not a first picture to keep).
inline constexpr float kFileCameraMinSurfaceShare = 0.999f;
// Each camera's sight costs a pass over the model: the default camera is chosen among a file's
// first kMaxFileCamerasJudged, and --camera list judges as many.
inline constexpr size_t kMaxFileCamerasJudged = 16;

struct SceneLoadOptions {
  // Host memory a scene file may take: the files it reads, its geometry with every instance
  // expanded and its decoded textures. Estimated from counts and image headers before any
  // geometry is expanded or any texture decoded; loadScene refuses a file above it with the bytes
  // needed. [kMinSceneMemoryBytes, kMaxSceneMemoryBytes].
  uint64_t maxMemoryBytes = defaultSceneMemoryLimit();
  // The frame's width / height, for the framing camera of a scene file, (0, 100].
  float aspect = 16.0f / 9.0f;
  GroundMode ground = GroundMode::Auto;
  CasterMode casters = CasterMode::Auto;
  // The file's camera to use (an index into Scene::fileCameras, as --camera takes it); unset: the
  // first file camera that sees the model (kFileCameraMinSurfaceShare), else the framing camera.
  std::optional<int> camera;
};

// A memory size as an option gives it (`option` names it in messages): a number of MiB ("512"),
// or a number with a binary unit K, M, G or T, optionally followed by B or iB ("1.5G", "512MiB",
// "2GB": G = 2^30 bytes alike). Throws Error naming the option, the text and the range above.
uint64_t parseMemorySize(std::string_view text, std::string_view option);
// Three significant digits in the largest binary unit that keeps them above 1: "3.26 GiB",
// "512 MiB", "812 bytes".
std::string memorySizeText(uint64_t bytes);

// A built-in scene's name, or a path to a .gltf, .glb or .obj file (scene_loaders.cpp). A file
// scene is named after its file and keeps the file's light (KHR_lights_punctual) where it has
// one, else a directional light from above; its camera follows SceneLoadOptions::camera, its
// enclosures, casters and ground SceneLoadOptions (docs/scenes.md, "Real models"). The options
// other than maxMemoryBytes do not change built-in scenes; a camera index for one is refused.
// Throws Error naming the file and the fault for malformed files (a hierarchy deeper than
// kMaxGltfNodeDepth, more memory than options.maxMemoryBytes, a file it names that is not a regular
// file, an allocation that fails), and the valid names and extensions for anything else.
Scene loadScene(std::string_view nameOrPath, const SceneLoadOptions& options = {});
// Checks, without loading, that loadScene can try `nameOrPath`: a built-in name or an existing
// file with a supported extension. Throws Error as loadScene does.
void checkSceneSource(std::string_view nameOrPath);

// Camera and light set from outside the scene (command line, settings file), for built-in and
// file scenes alike; unset fields keep the scene's own.
struct SceneOverrides {
  // The light's kind (--light): given alone, a point or spot light keeps the scene light's
  // position when it has one, else stands inside the scene (applyOverrides says where).
  std::optional<LightKind> lightKind;
  std::optional<glm::vec3> lightDirection;  // makes the light directional: the way it travels
  // Makes the light a spot light at this position (a point light with lightKind Point).
  std::optional<glm::vec3> lightPosition;
  std::optional<glm::vec3> lightTarget;   // spot: where it points (default: the model's centre)
  std::optional<float> spotAngleDegrees;  // spot: full cone angle, (0, 170]
  std::optional<glm::vec3> cameraPosition;
  std::optional<glm::vec3> cameraTarget;
  std::optional<float> cameraFovDegrees;  // vertical, (0, 170]
  std::optional<float> lightSize;         // Light::size, checked against the final light's kind

  bool empty() const;
};

// Checks each given value on its own, without a scene, so that front ends refuse bad values
// before any loading or GL work: vectors finite with every coordinate within
// kMaxWorldCoordinate, a light direction of non-zero length, angles in (0, 170], a light size
// within the widest kind's range. Throws Error naming the value and its range.
void validateOverrides(const SceneOverrides& overrides);

// Applies the overrides (validateOverrides first); throws Error as validateOverrides does and for
// both a light direction and a light position, a camera or spot light looking at its own
// position, a light size out of range for the final light's kind.
void applyOverrides(Scene& scene, const SceneOverrides& overrides);

// The scene's camera and light as overrides, every value given: applied to any scene, they
// give it this view (render's <stem>_settings.json reproduces a picture through them).
SceneOverrides viewOverrides(const Scene& scene);

}  // namespace penumbra
