// `penumbra bench`: the papers' performance experiments (--experiment, penumbra/compare/
// paper_bench.h) and every prefilter pass beside a minimal kernel with the same reads and writes
// (--passes, penumbra/gl/pass_bench.h), as ratios measured side by side, in JSON, CSV and HTML.
#include "bench_command.h"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "command_line.h"
#include "interrupt_cleanup.h"
#include "output_folder.h"
#include "penumbra/compare/paper_bench.h"
#include "penumbra/compare/paper_bench_report.h"
#include "penumbra/csv_field.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/pass_bench.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/text_file.h"
#include "render_options.h"
#include "scene_options.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

struct BenchOptions {
  bool passes = false;
  std::vector<std::string> experiments;  // ids, or "all"
  std::string commandLine;
  SceneOptions scene;
  TechniqueOptions technique{"esm,vsm,evsm4,msm", {}};
  RenderOptions render;
  int repeat = 3;
  // --passes takes each side's fastest frame: enough frames that both catch llvmpipe's fast mode
  // (docs/results/passes-llvmpipe-2026-12-06-fastest.md). A given --repeat is kept.
  static constexpr int kPassesRepeat = 15;
  OutputOptions output{"out/bench"};

  BenchOptions() {
    // The measurement: 2048², 9-tap box, trilinear (mips every frame).
    render.blurTaps = 9;
    render.blurKernel = "box";
  }
};

std::string experimentList() {
  std::string list;
  for (const std::string& id : compare::paperExperimentIds())
    list += (list.empty() ? "" : ", ") + id;
  return list;
}

// The scene as a bench measures it, shaped for frames of `aspect`; its warnings and notes printed.
Scene benchScene(const BenchOptions& o, float aspect) {
  Scene scene = loadScene(o.scene.scene, sceneLoadOptions(o.scene, aspect));
  applyOverrides(scene, sceneOverrides(o.scene));
  printSceneWarnings(scene);
  return scene;
}

void runPaperExperiments(const BenchOptions& o, float aspect) {
  std::vector<std::string> ids = o.experiments;
  if (ids.size() == 1 && ids[0] == "all") ids = compare::paperExperimentIds();
  compare::BenchSizes sizes;
  sizes.shadowMapSize = o.render.shadowSize;
  sizes.scalingShadowMapSize = std::min(o.render.shadowSize, sizes.scalingShadowMapSize);
  sizes.width = o.render.width;
  sizes.height = o.render.height;
  std::vector<compare::Experiment> experiments;
  for (const std::string& id : ids) experiments.push_back(compare::makePaperExperiment(id, sizes));
  const Scene scene = benchScene(o, aspect);
  CommandOutput output(o.output);
  InterruptCleanup interrupt;  // before the GL context: its driver threads inherit the mask
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  for (const compare::Experiment& e : experiments) {
    for (const compare::BenchCase& c : e.cases) renderer.validate(c.settings);
  }
  std::vector<compare::ExperimentResult> results;
  for (const compare::Experiment& e : experiments) {
    std::cout << e.title << " (" << e.cases.size() << " cases)\n" << std::flush;
    results.push_back(compare::runPaperExperiment(renderer, scene, e, o.repeat));
    for (const compare::CaseMeasurement& m : results.back().cases) {
      std::cout << std::fixed << std::setprecision(1) << "  " << m.benchCase.label << ": "
                << m.medianMs << " ms, " << std::setprecision(2) << m.timeRatio << "x "
                << e.baselineSeries << "'s time, " << m.memoryRatio << "x its memory\n";
    }
    for (const std::string& f : results.back().findings) std::cout << "  " << f << "\n";
  }
  const std::filesystem::path dir = output.begin(interrupt);
  compare::writePaperBenchReport(
      results, {renderer.deviceDescription(), scene.name, o.repeat, o.commandLine}, dir);
  output.finish(interrupt);
  std::cout << "\nwrote " << (output.target() / "index.html").string()
            << ", bench.json and bench.csv\n";
}

// Three significant digits down to a microsecond: a GPU's passes take hundredths of a
// millisecond, llvmpipe's hundreds of milliseconds, and one decimal would print the GPU's as 0.0.
std::string tableMilliseconds(double ms) {
  const int decimals = ms >= 100.0 ? 0 : ms >= 10.0 ? 1 : ms >= 1.0 ? 2 : 3;
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << ms;
  return text.str();
}

void runBench(const BenchOptions& o) {
  // The sizes given (the rest are defaults), checked before any work: the frame's aspect shapes
  // a scene file, and --camera list judges its cameras at it.
  const gl::RenderSettings given = toRenderSettings(o.render);
  const float aspect = float(given.width) / float(given.height);
  if (printCameraListIfAsked(o.scene, o.scene.scene, aspect)) return;
  if (o.passes == !o.experiments.empty()) {
    throw Error("choose one: --experiment ID[,ID...] or all (" + experimentList() +
                "), or --passes (each prefilter pass beside a minimal kernel)");
  }
  if (!o.passes) {
    runPaperExperiments(o, aspect);
    return;
  }
  if (printTechniqueListIfAsked(o.technique)) return;
  std::vector<Technique> techniques = selectedTechniques(o.technique);
  gl::RenderSettings settings = toRenderSettings(o.render);
  settings.params = selectedParams(o.technique, techniques);
  // PCF and the hard test filter after the test: "all" means the techniques with a prefilter,
  // naming them is an error before anything runs. With --filter sat, "all" also leaves out those
  // whose channels the summed-area filter cannot hold, and says so; naming one is refused with
  // the reason (Renderer::validate).
  const auto withoutPrefilter = [](Technique t) { return !prefiltersChannels(t); };
  if (o.technique.techniques == "all") {
    std::erase_if(techniques, withoutPrefilter);
    if (settings.filter == gl::FilterMode::SummedArea) {
      std::string leftOut;
      std::erase_if(techniques, [&](Technique t) {
        if (!summedAreaRefusal(t, settings.params)) return false;
        leftOut += (leftOut.empty() ? "" : ", ") + std::string(techniqueId(t));
        return true;
      });
      if (!leftOut.empty()) {
        std::cout << "left out: " << leftOut
                  << " (the summed-area filter cannot hold their channels)\n";
      }
    }
  } else if (const auto t = std::find_if(techniques.begin(), techniques.end(), withoutPrefilter);
             t != techniques.end()) {
    throw Error(std::string(techniqueId(*t)) +
                " has no prefilter passes to measure (it filters after the test): choose "
                "techniques that prefilter, or all");
  }
  const Scene scene = benchScene(o, aspect);
  gl::checkPassBenchable(scene, settings);  // before a GL context or the output exist
  CommandOutput output(o.output);
  InterruptCleanup interrupt;  // before the GL context: its driver threads inherit the mask
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  for (Technique t : techniques) {
    settings.technique = t;
    renderer.validate(settings);
  }
  const std::filesystem::path dir = output.begin(interrupt);
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  std::ostringstream csv;
  csv << "technique,format,pass,pass_ms,baseline,baseline_ms,ratio,yardstick,yardstick_ms,"
         "baseline_to_yardstick,pass_median_ms,baseline_median_ms,yardstick_median_ms\n";
  const std::string timing = gl::passTimingDescription(renderer);
  std::cout << "The fastest of " << o.repeat << " warm frames (" << gl::passSamplingDescription()
            << "), " << timing << ", on " << renderer.deviceDescription() << " (" << scene.name
            << ", " << settings.shadowMapSize << "², " << (2 * settings.blur.radius + 1) << "-tap "
            << (settings.blur.kernel == BlurKernel::Box ? "box" : "Gaussian") << " blur, "
            << filterModeName(settings.filter) << "):\n\n"
            << "| technique | format | pass | ms | minimal kernel | ms | ratio | yardstick | ms | "
               "minimal / yardstick |\n"
            << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (Technique t : techniques) {
    settings.technique = t;
    const gl::PassBenchResult r = gl::benchPasses(renderer, scene, settings, o.repeat);
    for (const gl::PassTiming& p : r.passes) {
      std::cout << std::fixed << "| " << techniqueId(t) << " | " << r.format << " | " << p.pass
                << " | " << tableMilliseconds(p.passMs()) << " | " << p.baseline << " | "
                << tableMilliseconds(p.baselineMs()) << " | " << std::setprecision(2) << p.ratio()
                << " | ";
      if (p.yardstick.empty()) {
        std::cout << "— | | |\n";
      } else {
        std::cout << p.yardstick << " | " << tableMilliseconds(p.yardstickMs()) << " | "
                  << std::setprecision(2) << p.baselineToYardstick() << " |\n";
      }
      // A row without a yardstick (mips, summed-area table) leaves its cells empty (CSV) or
      // null (JSON): no time was measured, and 0 would read as one.
      csv << techniqueId(t) << "," << csvField(r.format) << "," << csvField(p.pass) << ","
          << p.passMs() << "," << csvField(p.baseline) << "," << p.baselineMs() << "," << p.ratio()
          << "," << csvField(p.yardstick) << ",";
      if (p.yardstick.empty()) {
        csv << ",,";
      } else {
        csv << p.yardstickMs() << "," << p.baselineToYardstick() << ",";
      }
      csv << p.passTimes.medianMs << "," << p.baselineTimes.medianMs << ",";
      if (!p.yardstick.empty()) csv << p.yardstickTimes.medianMs;
      csv << "\n";
      const auto measured = [&](double v) {
        return p.yardstick.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(v);
      };
      rows.push_back({{"technique", techniqueId(t)},
                      {"format", r.format},
                      {"pass", p.pass},
                      {"pass_ms", p.passMs()},
                      {"baseline", p.baseline},
                      {"baseline_ms", p.baselineMs()},
                      {"ratio", p.ratio()},
                      {"yardstick", p.yardstick},
                      {"yardstick_ms", measured(p.yardstickMs())},
                      {"baseline_to_yardstick", measured(p.baselineToYardstick())},
                      {"pass_median_ms", p.passTimes.medianMs},
                      {"baseline_median_ms", p.baselineTimes.medianMs},
                      {"yardstick_median_ms", measured(p.yardstickTimes.medianMs)}});
    }
  }
  const nlohmann::ordered_json record = {
      {"experiment", "passes"},
      {"device", renderer.deviceDescription()},
      {"timing", "the fastest of the warm frames (" + gl::passSamplingDescription() +
                     "; medians beside), " + timing +
                     (renderer.timerQueriesMeasureExecution()
                          ? ""
                          : "; a software rasteriser's timer queries see only submission")},
      {"scene", scene.name},
      {"shadow_map_size", settings.shadowMapSize},
      {"blur_taps", 2 * settings.blur.radius + 1},
      {"blur_kernel", settings.blur.kernel == BlurKernel::Box ? "box" : "gaussian"},
      {"filter", filterModeName(settings.filter)},
      {"repeats", o.repeat},
      {"rows", rows}};
  writeTextFile(dir / "passes.json", record.dump(2) + "\n");
  writeTextFile(dir / "passes.csv", csv.str());
  output.finish(interrupt);
  std::cout << "\nwrote " << (output.target() / "passes.json").string() << " and passes.csv\n";
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd =
      app.add_subcommand("bench", "Performance experiments measured side by side in one run.");
  cmd->add_option("-e,--experiment", o->experiments,
                  "the papers' experiments to rerun, comma-separated, or all: " + experimentList())
      ->delimiter(',');
  cmd->add_flag("--passes", o->passes,
                "each prefilter pass (encode, blur, the fused encode + blur, mips or with --filter "
                "sat the summed-area table) beside a minimal kernel with the same reads and "
                "writes, as a ratio, and beside the independent yardstick's copy and blur "
                "(../shared/yardsticks/rawblur.c's kernels, 32-bit float texels)");
  addSceneOptions(*cmd, o->scene);
  addTechniqueOptions(*cmd, o->technique);
  addRenderOptions(*cmd, o->render);
  cmd->add_option("--repeat", o->repeat,
                  "timed frames after one warm-up: --experiment takes their medians; --passes "
                  "(15 frames unless given) the fastest frame's ratios (" +
                      gl::passSamplingDescription() + "), medians beside them in the CSV and JSON")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  addOutputOptions(*cmd, o->output, "the results");
  cmd->callback([o, cmd] {
    if (!o->experiments.empty()) {
      // The experiments fix their techniques, kernels and lookups; only the sizes are the user's.
      for (const char* fixedByExperiment :
           {"--technique", "--param", "--blur", "--blur-kernel", "--blur-sigma", "--filter",
            "--aniso", "--msaa", "--normal-offset", "--cascades", "--overlay"}) {
        if (cmd->count(fixedByExperiment) > 0) {
          throw Error(std::string(fixedByExperiment) +
                      " does not apply to --experiment: each experiment fixes its techniques, "
                      "kernels and lookups (--shadow-size, --width, --height, --scene and "
                      "--repeat apply)");
        }
      }
    }
    if (o->passes && cmd->count("--repeat") == 0) o->repeat = BenchOptions::kPassesRepeat;
    o->commandLine = givenCommandLine(*cmd);
    runBench(*o);
  });
}

}  // namespace penumbra::cli
