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

// compare's and tune's rule for soft shadows: with a light size (view.lightSize > 0) and no
// settings file, a --filter not given becomes trilinear (the filterable techniques widen their
// filter by mip level; bilinear cannot) and a --blur not given becomes none (the penumbra alone
// sets the filter's width, as the area-light reference has no prefilter). A settings file's
// values are the user's and are kept.
void applySoftShadowMeasurementDefaults(const CLI::App& command, const std::string& settingsFile,
                                        const SceneOverrides& view, gl::RenderSettings& settings);

}  // namespace penumbra::cli
