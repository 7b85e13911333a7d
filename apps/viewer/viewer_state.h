// Everything the viewer shows and edits, apart from GL objects: the settings (as saved and as the
// command line takes them), the camera and light being moved, what the scene area shows.
#pragma once

#include <deque>
#include <string>

#include "camera_control.h"
#include "display_image.h"
#include "penumbra/gl/settings_json.h"

namespace penumbra::viewer {

struct ViewerState {
  gl::Settings settings;  // settings.techniques.front() is the technique shown
  Scene scene;            // loaded from settings.scene, with settings.view applied
  Camera camera;          // the view being moved; starts as the scene's camera
  Light light;            // the light being moved; starts as the scene's light
  CameraMode cameraMode = CameraMode::Orbit;
  View view = View::Shaded;
  int channel = 0;     // View::Channel's technique channel
  int mapCascade = 0;  // the cascade View::ShadowMap and View::Channel show
  bool showPanel = true;
  // The split view: right of the divider (a share of the frame's width), this technique with
  // these parameters; left, the settings' technique.
  bool split = false;
  Technique splitTechnique = Technique::Pcf;
  TechniqueParams splitParams = defaultTechniqueParams();
  float divider = 0.5f;
  std::string settingsPath = "penumbra-viewer.json";  // the panel's save / load file
  std::string message;  // the last error or confirmation, shown in the panel
  bool messageIsError = false;
  // The last frames' per-pass times, oldest first: GPU timer queries (none where the device's
  // queries do not time execution: RenderResult::gpuTimes) and wall clock.
  std::deque<gl::PassTimes> gpuTimes;
  std::deque<gl::PassTimes> wallTimes;
  bool graphGpuTimes = false;
  // The window's last frames: the time each took to draw (events waited for aside), ms.
  std::deque<double> frameMs;
  std::string referenceStatus;  // the error view's reference: progress, or its time once done
  // The error-against-the-truth view: the trace's progress, or its time, the silhouettes left
  // out and the errors once done.
  std::string truthStatus;
  // A scene file's animation (Scene::animation): whether it plays (in real time; scripted runs
  // a frame at kClipFramesPerSecond) and the clip time the scene is posed at.
  bool playing = true;
  float clipSeconds = 0.0f;
};

// What the panel changed this frame, so that only what depends on it is redone.
struct Changes {
  bool scene = false;    // reload the scene (and take its camera and light)
  bool pose = false;     // pose the scene at ViewerState::clipSeconds
  bool render = false;   // render the frame again
  bool display = false;  // compose the scene area again from the last render
  bool saveSettings = false;
  bool loadSettings = false;
};

// A settings file for the viewer (the defaults when `path` is empty): one technique, a scene that
// loadScene can try; throws Error otherwise.
gl::Settings loadViewerSettings(const std::string& path);

// The settings with the current camera and light written into their view overrides and the split
// view's right side into "split": what a saved file must hold to reproduce this frame.
gl::Settings settingsToSave(const ViewerState& state);

// Moves a loaded file's split view (settings.split) into the state's split fields; a file without
// one turns the split view off.
void takeSplitSettings(ViewerState& state);

}  // namespace penumbra::viewer
