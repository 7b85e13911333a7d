// Merging the settings file with the command line.
#include "settings_options.h"

#include <algorithm>

#include "penumbra/error.h"
#include "penumbra/gl/render_setting_values.h"
#include "penumbra/params.h"

namespace penumbra::cli {

void addSettingsOption(CLI::App& app, std::string& path) {
  app.add_option("--settings", path,
                 "JSON settings file (keys are these options' names; the viewer saves one, "
                 "docs/viewer.md); options given on the command line override the file's values");
}

gl::Settings resolveSettings(const CLI::App& command, const std::string& path,
                             const SceneOptions& scene, const TechniqueOptions& technique,
                             const RenderOptions& render) {
  gl::Settings s;
  s.scene = scene.scene;
  s.techniques = selectedTechniques(technique);
  // Ranges and the cascade count the tuning options need are checked once the file is merged:
  // the file may supply the count.
  s.render = renderSettingsOf(render);
  s.render.params = defaultTechniqueParams();
  s.ground = parseGroundMode(scene.ground);
  s.casters = parseCasterMode(scene.casters);
  if (!path.empty()) {
    std::vector<std::string> given;
    for (std::string_view key : gl::settingsKeys()) {
      if (key == "param" || key == "light" || key == "camera") continue;  // merged below
      if (command.count("--" + std::string(key)) > 0) given.emplace_back(key);
    }
    // --blur on the command line means that width with its default sigma, not the file's.
    if (command.count("--blur") > 0 && command.count("--blur-sigma") == 0) {
      given.emplace_back("blur-sigma");
    }
    gl::applySettingsFile(path, s, given);
    // The file's "blur" sets its width's default sigma: a --blur-sigma given here stays.
    if (command.count("--blur-sigma") > 0)
      s.render.blur.sigma = renderSettingsOf(render).blur.sigma;
  }
  requireGivenOptionsApply(render, s.render);
  gl::validateRenderSettings(s.render);
  s.view = sceneOverrides(scene, s.view);
  validateOverrides(s.view);
  for (const std::string& assignment : technique.params) {
    applyParamAssignment(s.techniques, s.render.params, assignment);
  }
  for (Technique t : s.techniques) validateParams(t, s.render.params);
  return s;
}

void applySoftShadowMeasurementDefaults(const CLI::App& command, const std::string& settingsFile,
                                        const SceneOverrides& view, gl::RenderSettings& settings) {
  if (!view.lightSize || !(*view.lightSize > 0.0f) || !settingsFile.empty()) return;
  if (command.get_option("--filter")->count() == 0) settings.filter = FilterMode::Trilinear;
  if (command.get_option("--blur")->count() == 0) settings.blur.radius = 0;
}

}  // namespace penumbra::cli
