// Settings files: the scene, techniques, parameters, render settings, camera and light of a
// render as JSON whose keys are the command line's option names (docs/viewer.md, "Settings
// files"). `penumbra render --settings`, `penumbra compare --settings` and the viewer's save and
// load all go through here, so a file the viewer saves is one the command line accepts.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/gl/renderer.h"
#include "penumbra/scene.h"

namespace penumbra::gl {

// The viewer's split view (docs/viewer.md): right of the divider, this technique with these
// parameters, every other setting shared. render and compare check it and render the main
// settings only (the left side).
struct SplitSettings {
  Technique technique = Technique::Pcf;
  TechniqueParams params = defaultTechniqueParams();
  float divider = 0.5f;  // a share of the frame's width, [0, 1]
};

struct Settings {
  std::string scene = "backyard";  // a built-in name or a scene file's path
  std::vector<Technique> techniques{Technique::Evsm4};
  RenderSettings render;               // render.technique is unused: see techniques
  SceneOverrides view;                 // camera and light; unset: the scene's own
  GroundMode ground = GroundMode::Auto;  // what loading a scene file adds (SceneLoadOptions)
  CasterMode casters = CasterMode::Auto;
  std::optional<SplitSettings> split;  // "split": the viewer's right side
};

// The keys a settings file takes, each the name of a command-line option of render and compare
// ("shadow-size", "blur", ...), plus "param" (an object of technique objects), "light" and
// "camera" (as in a --view file). A file may also hold "split" (the viewer's split view:
// {"technique": id, "param": {...}, "divider": share}), no command-line option: it is checked
// like the rest and read into Settings::split, which render and compare do not render.
std::span<const std::string_view> settingsKeys();

// Applies the keys present in `json` to `settings`, except those named in `skip` (the command
// line's explicit options, which win). Throws Error with `source`, the key and the fault: invalid
// JSON (with its line and column), an unknown key or name (listing the valid ones), a value of the
// wrong type or out of its range (stating the range).
void applySettingsJson(std::string_view json, const std::string& source, Settings& settings,
                       std::span<const std::string> skip = {});
void applySettingsFile(const std::filesystem::path& path, Settings& settings,
                       std::span<const std::string> skip = {});

// Every key (the parameters of the listed techniques; light and camera where set), pretty-printed.
std::string settingsJson(const Settings& settings);
void writeSettingsFile(const std::filesystem::path& path, const Settings& settings);

// The "light" and "camera" objects of a settings or --view file:
// {"light": {"direction": [x,y,z]} or {"position": [...], "target": [...], "spot_angle": deg},
//  "camera": {"position": [...], "target": [...], "fov": deg}}; throws Error as above.
void applyViewFile(const std::filesystem::path& path, SceneOverrides& overrides);

}  // namespace penumbra::gl
