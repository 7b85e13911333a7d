// Command-line options that choose the scene and set its camera and light (render, compare):
// --scene NAME|PATH, --light KIND, --light-dir, --light-pos, --light-target, --spot-angle,
// --camera-pos,
// --camera-target, --camera-fov, --light-size and --view FILE.json holding the same settings;
// --max-memory bounds what loading a scene file may take.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "penumbra/gl/settings_json.h"
#include "penumbra/scene.h"

namespace penumbra::cli {

struct SceneOptions {
  std::string scene = "backyard";
  std::string viewFile;   // JSON; the command-line options take precedence over it
  std::string lightKind;  // directional, spot, point; empty: implied by --light-dir/--light-pos
  std::string lightDirection, lightPosition, lightTarget, cameraPosition, cameraTarget;  // "x,y,z"
  std::optional<float> spotAngle;  // degrees; unset: the scene's
  std::optional<float> cameraFov;
  std::optional<float> lightSize;  // Light::size
  std::string maxMemory;           // --max-memory as given; empty: defaultSceneMemoryLimit()
  std::string ground = "auto";     // --ground auto|on|off
  std::string casters = "auto";    // --casters auto|all
  std::string camera;              // --camera N|list; empty: SceneLoadOptions::camera's rule
};

void addSceneOptions(CLI::App& app, SceneOptions& options);

// `base` (a settings file's), then the view file, then the command line; throws Error naming the
// option or the file's key that is malformed.
SceneOverrides sceneOverrides(const SceneOptions& options, SceneOverrides base = {});

// How to load a scene file for frames of this aspect (width / height): --max-memory, --ground,
// --casters, --camera N. Throws Error for a size that is malformed or out of range, an unknown
// mode (listing the valid ones), a camera that is neither a number nor 'list'.
SceneLoadOptions sceneLoadOptions(const SceneOptions& options, float aspect);
// The same for settings merged with a settings file: its frame's aspect, ground and casters.
SceneLoadOptions sceneLoadOptions(const SceneOptions& options, const gl::Settings& resolved);

// --camera list: prints the scene file's cameras, the first kMaxFileCamerasJudged each with what
// it sees of the model at this aspect (and how many more it did not judge), and returns true;
// false when not asked.
bool printCameraListIfAsked(const SceneOptions& options, const std::string& scene, float aspect);

// Prints the scene's warnings and notes to stderr, one line each.
void printSceneWarnings(const Scene& scene);

}  // namespace penumbra::cli
