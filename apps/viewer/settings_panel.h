// The viewer's ImGui panel: scene, technique and every parameter from the parameter registry
// (penumbra/params.h: ranges, defaults and help are the registry's), render settings, camera and
// light, what the scene area shows, timings and memory, settings files.
#pragma once

#include "penumbra/gl/renderer.h"
#include "viewer_state.h"

namespace penumbra::viewer {

struct FrameStats {
  const gl::RenderResult* result = nullptr;  // the last render, if any
  std::string device;
};

// Draws the panel (at the window's right edge, `panelWidth` wide) and returns what changed.
Changes drawSettingsPanel(ViewerState& state, const FrameStats& stats, float panelWidth);

}  // namespace penumbra::viewer
