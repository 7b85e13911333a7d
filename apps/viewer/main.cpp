// `penumbra-viewer`: tune every technique live and see why it fails (docs/viewer.md).
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "penumbra/error.h"
#include "viewer.h"

int main(int argc, char** argv) {
  penumbra::viewer::ViewerOptions options;
  CLI::App app{"penumbra-viewer: filtered shadow maps, live (docs/viewer.md)"};
  app.add_option("--settings", options.settingsFile,
                 "JSON settings file as `penumbra render --settings` takes (and the viewer saves)");
  CLI::Option* frames = app.add_option("--frames", options.frames,
                                       "scripted: draw this many frames without input, then exit")
                            ->check(CLI::Range(1, 100000));
  app.add_option("--screenshot", options.screenshot,
                 "scripted: write the window as a PNG after the last frame")
      ->needs(frames);
  app.add_option("--save-settings", options.saveSettings,
                 "scripted: save the settings after the last frame, as the panel's save does")
      ->needs(frames);
  app.add_flag("--hide-panel", options.hidePanel,
               "start with the settings panel hidden (H toggles)");
  app.add_flag("--fly", options.fly, "start with the fly camera (W A S D Q E move it)");
  app.add_option("--show", options.show,
                 "what the scene area shows: shaded, visibility, error, failures, layers, "
                 "shadowmap, channel")
      ->capture_default_str();
  app.add_option("--split", options.split,
                 "TECHNIQUE: start in the split view, this technique right of the divider (same "
                 "parameters as the settings')");
  std::vector<int> probe;
  app.add_option("--probe", probe,
                 "X,Y: a frame pixel to show under the cursor from the start (for scripted runs)")
      ->delimiter(',')
      ->expected(2);
  app.add_option("--window-width", options.windowWidth, "window width in pixels")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  app.add_option("--window-height", options.windowHeight, "window height in pixels")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  std::string maxMemory;
  app.add_option("--max-memory", maxMemory,
                 "host memory a scene file may take (its files, geometry with every instance "
                 "expanded, decoded textures): MiB, or with a unit K, M, G or T; default half "
                 "this machine's memory, " +
                     penumbra::memorySizeText(penumbra::defaultSceneMemoryLimit()) +
                     " (docs/untrusted-input.md)");
  std::string scene, ground, casters, camera;
  app.add_option("--scene", scene,
                 "built-in scene or a .gltf, .glb or .obj file (default: the settings file's, "
                 "else backyard)");
  app.add_option("--ground", ground,
                 "auto: a ground plane under a scene file's model that stands on no floor of its "
                 "own; on; off (default: the settings file's, else auto; docs/scenes.md)");
  app.add_option("--casters", casters,
                 "auto: enclosures and unlit materials cast no shadows; all: every mesh casts "
                 "(default: the settings file's, else auto)");
  app.add_option("--camera", camera,
                 "N: start from the scene file's camera N (penumbra render --camera list names "
                 "them)");
  CLI11_PARSE(app, argc, argv);
  if (probe.size() == 2) {
    options.probeX = probe[0];
    options.probeY = probe[1];
  }
  try {
    if (!scene.empty()) options.scene = scene;
    if (!ground.empty()) options.ground = penumbra::parseGroundMode(ground);
    if (!casters.empty()) options.casters = penumbra::parseCasterMode(casters);
    if (!camera.empty()) {
      options.sceneLoad.camera = penumbra::parseCameraIndex(camera);
      if (!options.sceneLoad.camera) {
        throw penumbra::Error("--camera '" + camera + "' must be a camera's index (0, 1, ...)");
      }
    }
    if (!maxMemory.empty()) {
      options.sceneLoad.maxMemoryBytes = penumbra::parseMemorySize(maxMemory, "--max-memory");
    }
    penumbra::viewer::runViewer(options);
  } catch (const std::exception& e) {
    std::cerr << "penumbra-viewer: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
