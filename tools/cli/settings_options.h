// --settings FILE for the subcommands that render (render, compare): the settings file
// (penumbra/gl/settings_json.h, the viewer saves it) under the options given explicitly.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "penumbra/gl/settings_json.h"
#include "render_options.h"
#include "scene_options.h"
#include "technique_options.h"

namespace penumbra::cli {

void addSettingsOption(CLI::App& app, std::string& path);

// What the command renders: the options' defaults, overridden by the settings file at `path`
// (none when empty), overridden by the options given explicitly on `command`'s line (--param
// assignments apply on top of the file's parameters). Throws Error for bad options or a bad file.
gl::Settings resolveSettings(const CLI::App& command, const std::string& path,
                             const SceneOptions& scene, const TechniqueOptions& technique,
                             const RenderOptions& render);

}  // namespace penumbra::cli
