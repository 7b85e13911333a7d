// `penumbra bench --passes`: every prefilter pass beside a minimal kernel with the same reads and
// writes (penumbra/gl/pass_bench.h), printed as ratios and written as JSON and CSV.
#include "bench_command.h"

#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "output_folder.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/pass_bench.h"
#include "penumbra/gl/renderer.h"
#include "render_options.h"
#include "scene_options.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

struct BenchOptions {
  bool passes = false;
  SceneOptions scene;
  TechniqueOptions technique{"esm,vsm,evsm4,msm", {}};
  RenderOptions render;
  int repeat = 3;
  std::string outDir = "out/bench";

  BenchOptions() {
    // The measurement: 2048², 9-tap box, trilinear (mips every frame).
    render.blurTaps = 9;
    render.blurKernel = "box";
  }
};

void runBench(const BenchOptions& o) {
  if (!o.passes) {
    throw Error("choose an experiment: --passes (each prefilter pass beside a minimal kernel)");
  }
  if (printTechniqueListIfAsked(o.technique)) return;
  const std::vector<Technique> techniques = selectedTechniques(o.technique);
  gl::RenderSettings settings = toRenderSettings(o.render);
  settings.params = selectedParams(o.technique, techniques);
  Scene scene = loadScene(o.scene.scene);
  applyOverrides(scene, sceneOverrides(o.scene));
  checkOutputPath(o.outDir);

  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  for (Technique t : techniques) {
    settings.technique = t;
    renderer.validate(settings);
  }
  const std::filesystem::path dir = createOutputFolder(o.outDir);
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  std::ostringstream csv;
  csv << "technique,format,pass,pass_ms,baseline,baseline_ms,ratio\n";
  std::cout << "Wall-clock medians of " << o.repeat << " warm frames on "
            << renderer.deviceDescription() << " (" << scene.name << ", "
            << settings.shadowMapSize << "², " << (2 * settings.blur.radius + 1) << "-tap "
            << (settings.blur.kernel == BlurKernel::Box ? "box" : "Gaussian") << " blur, "
            << filterModeName(settings.filter) << "):\n\n"
            << "| technique | format | pass | ms | minimal kernel | ms | ratio |\n"
            << "| --- | --- | --- | --- | --- | --- | --- |\n";
  for (Technique t : techniques) {
    settings.technique = t;
    const gl::PassBenchResult r = gl::benchPasses(renderer, scene, settings, o.repeat);
    for (const gl::PassTiming& p : r.passes) {
      std::cout << std::fixed << std::setprecision(1) << "| " << techniqueId(t) << " | "
                << r.format << " | " << p.pass << " | " << p.passMs << " | " << p.baseline
                << " | " << p.baselineMs << " | " << std::setprecision(2) << p.ratio()
                << " |\n";
      csv << techniqueId(t) << "," << r.format << "," << p.pass << "," << p.passMs << ","
          << p.baseline << "," << p.baselineMs << "," << p.ratio() << "\n";
      rows.push_back({{"technique", techniqueId(t)},
                      {"format", r.format},
                      {"pass", p.pass},
                      {"pass_ms", p.passMs},
                      {"baseline", p.baseline},
                      {"baseline_ms", p.baselineMs},
                      {"ratio", p.ratio()}});
    }
  }
  const nlohmann::ordered_json record = {
      {"experiment", "passes"},
      {"device", renderer.deviceDescription()},
      {"timing", "wall-clock medians (glFinish around each pass); llvmpipe's timer queries see "
                 "only submission"},
      {"scene", scene.name},
      {"shadow_map_size", settings.shadowMapSize},
      {"blur_taps", 2 * settings.blur.radius + 1},
      {"blur_kernel", settings.blur.kernel == BlurKernel::Box ? "box" : "gaussian"},
      {"filter", filterModeName(settings.filter)},
      {"repeats", o.repeat},
      {"rows", rows}};
  std::ofstream(dir / "passes.json") << record.dump(2) << "\n";
  std::ofstream(dir / "passes.csv") << csv.str();
  std::cout << "\nwrote " << (dir / "passes.json").string() << " and passes.csv\n";
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Performance experiments measured side by side in one run.");
  cmd->add_flag("--passes", o->passes,
                "each prefilter pass (encode, blur, mips) beside a minimal kernel with the same "
                "reads and writes, as a ratio");
  addSceneOptions(*cmd, o->scene);
  addTechniqueOptions(*cmd, o->technique);
  addRenderOptions(*cmd, o->render);
  cmd->add_option("--repeat", o->repeat, "timed frames after one warm-up (medians)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("-o,--out", o->outDir, "output folder")->capture_default_str();
  cmd->callback([o] { runBench(*o); });
}

}  // namespace penumbra::cli
