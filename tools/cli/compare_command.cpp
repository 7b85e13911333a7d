// `penumbra compare`: parses options, runs penumbra::compare, writes the report.
#include "compare_command.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "interrupt_cleanup.h"
#include "output_folder.h"
#include "penumbra/compare/comparison.h"
#include "penumbra/compare/report.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/params.h"
#include "progress_bar.h"
#include "render_options.h"
#include "scene_options.h"
#include "settings_options.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

struct CompareOptions {
  SceneOptions scene;
  TechniqueOptions technique{"all", {}};
  RenderOptions render = measurementRenderDefaults();
  int supersample = 4;
  int areaSamples = kMinAreaLightSamples;
  std::string truth = "raytraced";
  int truthSamples = truth::kDefaultTrueShadowLightSamples;
  int frames = 4;
  double tau = 0.05;
  OutputOptions output{"out/compare"};
  bool quiet = false;
  std::string settingsFile;
  const CLI::App* command = nullptr;  // to tell options given explicitly from defaults
};

// Whether the settings file (already checked by resolveSettings) gives PCF parameters: the
// viewer writes every parameter of each technique it lists.
bool settingsFileSetsPcfParams(const std::string& path) {
  if (path.empty()) return false;
  std::ifstream in(path, std::ios::binary);
  const nlohmann::json file = nlohmann::json::parse(in);
  const auto params = file.find("param");
  if (params == file.end() || !params->is_object()) return false;
  const auto pcf = params->find(std::string(techniqueId(Technique::Pcf)));
  return pcf != params->end() && pcf->is_object() && !pcf->empty();
}

void runCompare(const CompareOptions& o) {
  if (printTechniqueListIfAsked(o.technique)) return;
  compare::ComparisonRequest request;
  const gl::Settings resolved =
      resolveSettings(*o.command, o.settingsFile, o.scene, o.technique, o.render);
  request.scene = resolved.scene;
  checkSceneSource(request.scene);  // unknown scenes and missing files fail before anything else
  const float aspect = float(resolved.render.width) / float(resolved.render.height);
  if (printCameraListIfAsked(o.scene, request.scene, aspect)) return;
  request.sceneLoad = sceneLoadOptions(o.scene, resolved);
  request.view = resolved.view;
  request.techniques = resolved.techniques;
  // A PCF parameter the user set (--param or the settings file) is used as given: PCF then keeps
  // all of its own settings and is no longer matched to the prefilter (the report says so).
  if (settingsFileSetsPcfParams(o.settingsFile)) request.matchPcfKernel = false;
  for (const std::string& assignment : o.technique.params) {
    const std::vector<Technique> targets = assignmentTargets(request.techniques, assignment);
    if (std::find(targets.begin(), targets.end(), Technique::Pcf) != targets.end()) {
      request.matchPcfKernel = false;
    }
  }
  request.settings = resolved.render;
  applySoftShadowMeasurementDefaults(*o.command, o.settingsFile, request.view, request.settings);
  request.supersample = o.supersample;
  request.areaLightSamples = o.areaSamples;
  request.truth = compare::parseTruthKind(o.truth);
  request.truthLightSamples = o.truthSamples;
  if (request.truth == compare::TruthKind::RayTraced) {
    truth::checkTrueShadowLightSamples(request.truthLightSamples);  // before any GL work
  }
  request.pathFrames = o.frames;
  request.tau = o.tau;

  CommandOutput output(o.output);  // a bad --out fails before any GL work
  InterruptCleanup interrupt;      // before the GL context: its driver threads inherit the mask
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  compare::validateRequest(request, renderer);
  const std::filesystem::path staging = output.begin(interrupt);
  compare::ComparisonResult result;
  {
    ProgressBar bar(o.quiet);
    result = compare::runComparison(
        request, renderer,
        [&](int done, int total, const std::string& step) { bar.update(done, total, step); });
  }
  printSceneWarnings(result.scene);
  if (const std::string w = translucencyWarning(result.scene, request.techniques); !w.empty()) {
    std::cerr << "penumbra: warning: " << w << "\n";
  }
  if (result.shadowedWarning) std::cout << "warning: " << *result.shadowedWarning << "\n";
  compare::writeReportFiles(result, staging);
  output.finish(interrupt);
  if (!o.quiet) {
    std::cout << "wrote " << (output.target() / "index.html").string() << "\n";
  }
}

}  // namespace

void registerCompareCommand(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Measure techniques against the ray-traced true shadow, the exact filtered reference and a "
      "supersampled ground truth; writes an HTML report with images, error maps, metrics and "
      "plots. Its defaults differ from render's on purpose (the values below): a smaller frame "
      "and shadow map, a box kernel and bilinear lookups keep the measurement of every technique "
      "against its references within seconds on a CPU's GL; render's (960x540, 2048, Gaussian, "
      "trilinear) make "
      "pictures. Give render's values here to measure the picture render makes.");
  addSceneOptions(*cmd, o->scene);
  addTechniqueOptions(*cmd, o->technique);
  addRenderOptions(*cmd, o->render);
  addSettingsOption(*cmd, o->settingsFile);
  o->command = cmd;
  cmd->add_option("--supersample", o->supersample, "ground-truth sub-pixels per side, 1..8")
      ->capture_default_str();
  cmd->add_option("--area-samples", o->areaSamples,
                  "with --light-size: point samples of the area-light reference, side^2 with side "
                  "in [8, 32]")
      ->capture_default_str();
  cmd->add_option("--truth", o->truth,
                  "the primary reference: raytraced (the true shadow from the scene's geometry, "
                  "Embree; the ranking is by it) or none (the filtered reference ranks)")
      ->capture_default_str();
  cmd->add_option("--truth-samples", o->truthSamples,
                  "with a light size: the true shadow's light samples per sub-pixel, side^2 with "
                  "side in [1, 64]")
      ->capture_default_str();
  cmd->add_option("--frames", o->frames, "camera-path frames for flicker, 2..32")
      ->capture_default_str();
  cmd->add_option("--tau", o->tau, "leak / over-darkening threshold on visibility")
      ->capture_default_str();
  addOutputOptions(*cmd, o->output, "the report");
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  cmd->callback([o] { runCompare(*o); });
}

}  // namespace penumbra::cli
