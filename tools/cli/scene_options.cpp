// Scene and view options. The view file is JSON (docs/scenes.md, read by
// penumbra/gl/settings_json.h): {"light": {"direction": [x, y, z]} or {"position": [...],
// "target": [...], "spot_angle": deg, optional "kind": directional|spot|point, optional "size":
// Light::size}, "camera": {"position": [x, y, z], "target": [...], "fov": deg}}
#include "scene_options.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gl/settings_json.h"

namespace penumbra::cli {
namespace {

glm::vec3 parseVector(const std::string& text, const std::string& option) {
  std::istringstream in(text);
  glm::vec3 v;
  char comma1 = 0, comma2 = 0;
  in >> v.x >> comma1 >> v.y >> comma2 >> v.z;
  if (!in || comma1 != ',' || comma2 != ',' || !(in >> std::ws).eof()) {
    throw Error(option + " '" + text + "' must be three numbers X,Y,Z");
  }
  return v;
}

}  // namespace

void addSceneOptions(CLI::App& app, SceneOptions& o) {
  app.add_option("-s,--scene", o.scene,
                 "built-in scene ('list' names them), or a .gltf, .glb or .obj file")
      ->capture_default_str();
  app.add_option("--view", o.viewFile,
                 "JSON file with the light and camera: {\"light\": {\"direction\": [x,y,z]}, "
                 "\"camera\": {\"position\": [x,y,z], \"target\": [x,y,z]}} (docs/scenes.md)");
  app.add_option("--light", o.lightKind,
                 "light kind: directional, spot or point (point: omnidirectional, at --light-pos "
                 "or the scene light's position; docs/renderer.md)");
  app.add_option("--light-dir", o.lightDirection,
                 "X,Y,Z: a directional light travelling this way (replaces the scene's light)");
  app.add_option("--light-pos", o.lightPosition,
                 "X,Y,Z: a spot light here, aimed at --light-target or the scene's centre (a "
                 "point light with --light point)");
  app.add_option("--light-target", o.lightTarget, "X,Y,Z: where the spot light points");
  app.add_option("--spot-angle", o.spotAngle, "spot light's full cone angle in degrees, (0, 170]");
  app.add_option("--light-size", o.lightSize,
                 "soft shadows: spot light's disk diameter in world units, [0, 10]; directional "
                 "light's angular diameter as a tangent, [0, 0.5]; point light's sphere diameter, "
                 "[0, 10] (docs/reference.md)");
  app.add_option("--camera-pos", o.cameraPosition, "X,Y,Z: the camera's position");
  app.add_option("--camera-target", o.cameraTarget, "X,Y,Z: the point the camera looks at");
  app.add_option("--camera-fov", o.cameraFov, "vertical field of view in degrees, (0, 170]");
  app.add_option("--max-memory", o.maxMemory,
                 "host memory a scene file may take (its files, geometry with every instance "
                 "expanded, decoded textures): MiB, or with a unit K, M, G or T; default half "
                 "this machine's memory, " +
                     memorySizeText(defaultSceneMemoryLimit()) + " (docs/untrusted-input.md)");
  app.add_option("--ground", o.ground,
                 "auto: a ground plane under a scene file's model that stands on no floor of "
                 "its own; on; off (docs/scenes.md, \"Real models\")")
      ->capture_default_str();
  app.add_option("--casters", o.casters,
                 "auto: geometry enclosing a scene file's model (a sky dome or box) and unlit "
                 "materials cast no shadows; all: every mesh casts")
      ->capture_default_str();
  app.add_option("--camera", o.camera,
                 "N: a scene file's camera N (default: the first that sees the whole model, "
                 "else a camera framing the model to 80% of the frame); list: name them with "
                 "what they see");
}

SceneLoadOptions sceneLoadOptions(const SceneOptions& o, float aspect) {
  SceneLoadOptions options;
  if (!o.maxMemory.empty()) options.maxMemoryBytes = parseMemorySize(o.maxMemory, "--max-memory");
  options.aspect = aspect;
  options.ground = parseGroundMode(o.ground);
  options.casters = parseCasterMode(o.casters);
  if (!o.camera.empty() && o.camera != "list") {
    options.camera = parseCameraIndex(o.camera);
    if (!options.camera) {
      throw Error("--camera '" + o.camera + "' must be a camera's index (0, 1, ...) or 'list'");
    }
  }
  return options;
}

SceneLoadOptions sceneLoadOptions(const SceneOptions& o, const gl::Settings& resolved) {
  SceneLoadOptions options =
      sceneLoadOptions(o, float(resolved.render.width) / float(resolved.render.height));
  options.ground = resolved.ground;
  options.casters = resolved.casters;
  return options;
}

bool printCameraListIfAsked(const SceneOptions& o, const std::string& source, float aspect) {
  if (o.camera != "list") return false;
  SceneOptions listing = o;
  listing.camera.clear();
  const Scene scene = loadScene(source, sceneLoadOptions(listing, aspect));
  // Why a camera of the file is not listed (not perspective, a field of view out of range).
  for (const std::string& w : scene.warnings) std::cerr << "penumbra: warning: " << w << "\n";
  if (scene.fileCameras.empty()) {
    std::cout << source << " defines no cameras; the default camera frames the model\n";
    return true;
  }
  const size_t count = scene.fileCameras.size();
  const size_t judged = std::min(count, kMaxFileCamerasJudged);
  std::cout << source << " defines " << count << (count == 1 ? " camera" : " cameras")
            << ", numbered as --camera takes them (what each sees of the model at aspect " << aspect
            << "):\n";
  for (size_t i = 0; i < judged; ++i) {
    const NamedCamera& c = scene.fileCameras[i];
    const CameraSight sight = cameraSight(scene, c.camera, aspect);
    std::cout << "  " << i << "  " << (c.name.empty() ? "(unnamed)" : c.name) << "  at "
              << c.camera.position.x << "," << c.camera.position.y << "," << c.camera.position.z
              << ", fov " << c.camera.verticalFovDegrees
              << " deg: " << std::floor(1000.0f * sight.surfaceShare) / 10.0f
              << "% of the model's surface, " << int(std::lround(100.0f * sight.frameShare))
              << "% of the frame\n";
  }
  if (judged < count) {
    // Each sight costs a pass over the model, as when the default camera is chosen.
    std::cout << "  " << count - judged << " more (" << judged << " to " << count - 1
              << ") not judged: the default is chosen among the first " << judged
              << "; --camera N uses any\n";
  }
  return true;
}

SceneOverrides sceneOverrides(const SceneOptions& o, SceneOverrides base) {
  SceneOverrides overrides = std::move(base);
  if (!o.viewFile.empty()) gl::applyViewFile(o.viewFile, overrides);
  // A light kind given on the command line replaces the file's light entirely.
  // A direction or position without --light sets the kind it implies (directional, spot).
  if (o.lightKind.empty() && (!o.lightDirection.empty() || !o.lightPosition.empty())) {
    overrides.lightKind.reset();
  }
  if (!o.lightKind.empty()) {
    overrides.lightKind = parseLightKind(o.lightKind);
    if (*overrides.lightKind == LightKind::Directional) overrides.lightPosition.reset();
    if (*overrides.lightKind != LightKind::Directional) overrides.lightDirection.reset();
    if (*overrides.lightKind == LightKind::Point) {
      overrides.lightTarget.reset();
      overrides.spotAngleDegrees.reset();
    }
  }
  if (!o.lightDirection.empty()) {
    overrides.lightPosition.reset();
    overrides.lightTarget.reset();
    overrides.spotAngleDegrees.reset();
    overrides.lightDirection = parseVector(o.lightDirection, "--light-dir");
  }
  if (!o.lightPosition.empty()) {
    overrides.lightDirection.reset();
    overrides.lightPosition = parseVector(o.lightPosition, "--light-pos");
  }
  if (!o.lightTarget.empty()) overrides.lightTarget = parseVector(o.lightTarget, "--light-target");
  if (o.spotAngle) overrides.spotAngleDegrees = o.spotAngle;
  if (!o.cameraPosition.empty()) {
    overrides.cameraPosition = parseVector(o.cameraPosition, "--camera-pos");
  }
  if (!o.cameraTarget.empty()) {
    overrides.cameraTarget = parseVector(o.cameraTarget, "--camera-target");
  }
  if (o.cameraFov) overrides.cameraFovDegrees = o.cameraFov;
  if (o.lightSize) overrides.lightSize = o.lightSize;
  return overrides;
}

void printSceneWarnings(const Scene& scene) {
  for (const std::string& w : scene.warnings) std::cerr << "penumbra: warning: " << w << "\n";
  for (const std::string& n : scene.notes) std::cerr << "penumbra: note: " << n << "\n";
}

}  // namespace penumbra::cli
