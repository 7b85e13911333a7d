// The viewer's loop: load the scene, render when something the frame depends on changes, show
// the frame or a diagnostic in the scene area at the window's top left, the panel at its right.
#pragma once

#include <optional>
#include <string>

#include "penumbra/scene.h"

namespace penumbra::viewer {

struct ViewerOptions {
  std::string settingsFile;  // loaded at start; empty: the defaults
  int frames = 0;            // > 0: scripted, exits after this many frames
  std::string screenshot;    // scripted: the window's PNG written after the last frame
  std::string saveSettings;  // scripted: the settings file saved after the last frame
  bool hidePanel = false;
  bool fly = false;              // start with the fly camera (W A S D Q E) rather than orbit
  std::string show = "shaded";   // what the scene area shows at start (display_image.h viewId)
  std::string split;             // a technique id: the split view's right side from the start
  int probeX = -1, probeY = -1;  // >= 0: the pixel under the cursor at start (scripted runs)
  int windowWidth = 1280;
  int windowHeight = 800;
  // --max-memory: what loading a scene file may take; --camera: the file's camera to start from
  // (a scene opened later from the panel starts from its default camera).
  SceneLoadOptions sceneLoad;
  // --scene, --ground, --casters: in place of the settings file's.
  std::optional<std::string> scene;
  std::optional<GroundMode> ground;
  std::optional<CasterMode> casters;
};

// Runs until the window closes (or the scripted frames are done); throws Error for bad settings
// at start and for a window or context that cannot be made.
void runViewer(const ViewerOptions& options);

}  // namespace penumbra::viewer
