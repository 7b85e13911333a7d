// `penumbra tune`: parses options, runs penumbra::tune's units (all, or one shard's), writes the
// unit folders and, unless sharded, the report; `--merge` assembles shards' units into it.
#include "tune_command.h"

#include <iostream>
#include <memory>
#include <optional>

#include "interrupt_cleanup.h"
#include "output_folder.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/tune/tune.h"
#include "penumbra/tune/tune_files.h"
#include "progress_bar.h"
#include "render_options.h"
#include "scene_options.h"
#include "settings_options.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

// The library's defaults, stated once (tune::TuneRequest).
const tune::TuneRequest kDefaults;

struct TuneOptions {
  std::vector<std::string> scenes;
  SceneOptions scene;
  TechniqueOptions technique{"all", {}};
  RenderOptions render = measurementRenderDefaults();
  std::string settingsFile;
  std::vector<std::string> only;
  std::string truth{tune::targetName(kDefaults.target)};
  std::string objective{tune::errorMeasureName(kDefaults.measure)};
  double leakWeight = kDefaults.leakWeight;
  std::optional<double> budgetMs;
  std::optional<double> budgetMib;
  int evaluations = kDefaults.evaluations;
  int frames = kDefaults.frames;
  int supersample = kDefaults.supersample;
  int truthSamples = kDefaults.truthLightSamples;
  int areaSamples = kDefaults.areaLightSamples;
  double tau = kDefaults.tau;
  double searchScale = kDefaults.searchScale;
  double maxSlowdown = kDefaults.maxSlowdown;
  std::string shard;
  std::vector<std::string> merge;
  OutputOptions output{"out/tune"};
  bool quiet = false;
  const CLI::App* command = nullptr;
};

// The options a merge takes; any other given with --merge is refused (the shards decided them).
bool mergeAllows(const std::string& name) {
  return name == "--merge" || name == "--out" || name == "--force" || name == "--quiet";
}

void runMerge(const TuneOptions& o) {
  for (const CLI::Option* option : o.command->get_options()) {
    if (option->count() > 0 && !mergeAllows(option->get_name())) {
      throw Error("--merge combines finished shards: " + option->get_name() +
                  " belongs to the runs that made them (give --merge, --out, --force, --quiet)");
    }
  }
  std::vector<std::filesystem::path> shards(o.merge.begin(), o.merge.end());
  CommandOutput output(o.output);
  InterruptCleanup interrupt;
  const std::filesystem::path staging = output.begin(interrupt);
  tune::gatherUnits(shards, staging);
  tune::writeTuneReport(staging);
  output.finish(interrupt);
  if (!o.quiet) std::cout << "wrote " << (output.target() / "index.html").string() << "\n";
}

tune::TuneRequest requestOf(const TuneOptions& o) {
  SceneOptions scene = o.scene;
  if (!o.scenes.empty()) scene.scene = o.scenes.front();
  const gl::Settings resolved =
      resolveSettings(*o.command, o.settingsFile, scene, o.technique, o.render);
  tune::TuneRequest r;
  r.scenes = o.scenes.empty() ? std::vector<std::string>{resolved.scene} : o.scenes;
  r.sceneLoad = sceneLoadOptions(o.scene, resolved);
  r.view = resolved.view;
  r.techniques = resolved.techniques;
  r.settings = resolved.render;
  applySoftShadowMeasurementDefaults(*o.command, o.settingsFile, r.view, r.settings);
  r.only = o.only;
  r.target = tune::parseTarget(o.truth);
  r.measure = tune::parseErrorMeasure(o.objective);
  r.leakWeight = o.leakWeight;
  r.budgetMs = o.budgetMs;
  r.budgetMib = o.budgetMib;
  r.frames = o.frames;
  r.supersample = o.supersample;
  r.truthLightSamples = o.truthSamples;
  r.areaLightSamples = o.areaSamples;
  r.tau = o.tau;
  r.evaluations = o.evaluations;
  r.searchScale = o.searchScale;
  r.maxSlowdown = o.maxSlowdown;
  tune::validateTuneRequest(r);
  return r;
}

void printSummary(const tune::UnitResult& r) {
  std::cout << tune::describeSpace(r.space);
  std::cout << r.sceneName << " " << techniqueId(r.unit.technique) << ": ";
  const tune::Measurement& d = r.defaultAtUserSize;
  if (d.measured) {
    std::cout << "default " << d.tuneError << " (held out " << d.heldOutError << ")";
  } else {
    std::cout << "default refused (" << d.status << ")";
  }
  if (r.bestAtUserSize) {
    std::cout << " -> tuned " << r.bestAtUserSize->tuneError << " (held out "
              << r.bestAtUserSize->heldOutError << "), " << r.bestAtUserSize->timeMs << " ms, "
              << double(r.bestAtUserSize->memoryBytes) / (1024.0 * 1024.0) << " MiB";
  } else {
    std::cout << " -> no eligible setting (tune.json says why)";
  }
  std::cout << " [" << r.evaluations.size() << " evaluations, " << r.seconds << " s]" << std::endl;
}

void runTune(const TuneOptions& o) {
  if (!o.merge.empty()) {
    runMerge(o);
    return;
  }
  if (printTechniqueListIfAsked(o.technique)) return;
  const tune::TuneRequest request = requestOf(o);
  if (o.scene.camera == "list") {
    const float aspect = float(request.settings.width) / float(request.settings.height);
    for (const std::string& source : request.scenes)
      printCameraListIfAsked(o.scene, source, aspect);
    return;
  }
  std::vector<tune::WorkUnit> units = tune::workUnits(request);
  const bool sharded = !o.shard.empty();
  if (sharded) units = tune::shardUnits(units, tune::parseShard(o.shard));

  CommandOutput output(o.output);  // a bad --out fails before any GL work
  InterruptCleanup interrupt;      // before the GL context: its driver threads inherit the mask
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  const std::filesystem::path staging = output.begin(interrupt);
  tune::createUnitsFolder(staging);
  {
    ProgressBar bar(o.quiet);
    tune::runUnits(
        request, units, renderer,
        [&](tune::UnitResult r) {
          tune::writeUnitFiles(request, r, staging);
          if (!o.quiet) printSummary(r);
        },
        [&](int done, int total, const std::string& step) { bar.update(done, total, step); },
        [&](const Scene& scene) {
          bar.breakLine();
          printSceneWarnings(scene);
        });
  }
  if (!sharded) tune::writeTuneReport(staging);
  output.finish(interrupt);
  if (!o.quiet) {
    std::cout << "wrote " << (sharded ? output.target() : output.target() / "index.html").string()
              << "\n";
  }
}

}  // namespace

void registerTuneCommand(CLI::App& app) {
  auto o = std::make_shared<TuneOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tune",
      "Search each technique's parameters for the least error against the ray-traced truth along "
      "the scene's camera path, within time and memory budgets; writes the best settings "
      "(best/<technique>.json, loadable by render, compare and the viewer), every evaluation "
      "(tune.json) and a report with the quality-cost frontier (index.html).");
  addSceneOptions(*cmd, o->scene);
  // Several scenes: --scene repeated (a corpus; units are scene x technique).
  cmd->remove_option(cmd->get_option("--scene"));
  cmd->add_option("-s,--scene", o->scenes,
                  "built-in scene or a .gltf, .glb or .obj file; repeat for several (default: "
                  "backyard)");
  addTechniqueOptions(*cmd, o->technique);
  addRenderOptions(*cmd, o->render);
  addSettingsOption(*cmd, o->settingsFile);
  o->command = cmd;
  cmd->add_option("--only", o->only,
                  "search only these dimensions (parameter or render-option names, e.g. "
                  "minVariance,normal-offset); the others keep the given values")
      ->delimiter(',');
  cmd->add_option("--truth", o->truth,
                  "the target: raytraced (the true shadow, Embree) or filtered (the supersampled "
                  "filtered reference of the given settings)")
      ->capture_default_str();
  cmd->add_option("--objective", o->objective,
                  "rmse, leak-weighted (a leak counts --leak-weight times) or flicker (RMSE plus "
                  "the frame-to-frame change beyond the target's)")
      ->capture_default_str();
  cmd->add_option("--leak-weight", o->leakWeight,
                  "leak-weighted: a leak's squared error counts this many times, [1, 100]")
      ->capture_default_str();
  cmd->add_option("--budget-ms", o->budgetMs, "no returned setting takes longer per warm frame");
  cmd->add_option("--budget-mib", o->budgetMib,
                  "no returned setting allocates more (the up-front estimate)");
  cmd->add_option("--evaluations", o->evaluations,
                  "settings measured per technique, the given one included, [1, 10000]")
      ->capture_default_str();
  cmd->add_option("--frames", o->frames,
                  "camera-path frames, [2, 32]: the first half (rounded up) tunes, the rest is "
                  "held out")
      ->capture_default_str();
  cmd->add_option("--supersample", o->supersample, "the target's sub-pixels per side, [1, 8]")
      ->capture_default_str();
  cmd->add_option("--truth-samples", o->truthSamples,
                  "with a light size: the true shadow's light samples per sub-pixel")
      ->capture_default_str();
  cmd->add_option("--area-samples", o->areaSamples,
                  "with a light size and --truth filtered: the area-light reference's samples")
      ->capture_default_str();
  cmd->add_option("--tau", o->tau, "leak / over-darkening threshold of the reported shares")
      ->capture_default_str();
  cmd->add_option("--search-scale", o->searchScale,
                  "the search's frame size as a share of --width x --height, (0, 1]; the result "
                  "is measured again at full size")
      ->capture_default_str();
  cmd->add_option("--max-slowdown", o->maxSlowdown,
                  "a setting whose first frame takes longer than this many times the given "
                  "setting's frame (and over 1 s) is not searched further, [1, 1e6]")
      ->capture_default_str();
  cmd->add_option("--shard", o->shard,
                  "K/N: run only the K-th of N shares of the scene x technique units (a cluster "
                  "job array's task); the output holds the units, --merge makes the report");
  cmd->add_option("--merge", o->merge,
                  "shard output folders to combine into one report (the same as a single run)")
      ->expected(1, -1);
  addOutputOptions(*cmd, o->output, "the tuned settings and the report");
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  cmd->callback([o] { runTune(*o); });
}

}  // namespace penumbra::cli
