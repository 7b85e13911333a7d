// `penumbra render`: parses options, calls penumbra::gl::Renderer, writes the images and record.
#include "render_command.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "output_folder.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/render_record.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/image_io.h"
#include "render_options.h"
#include "scene_options.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

struct RenderCommandOptions {
  SceneOptions scene;
  TechniqueOptions technique{"evsm4", {}};
  RenderOptions render;
  std::string outDir = "out/render";
  int repeat = 1;
};

void runRender(const RenderCommandOptions& options) {
  if (options.scene.scene == "list") {
    for (std::string_view name : builtinSceneNames()) {
      std::cout << name << "  " << makeBuiltinScene(name).description << "\n";
    }
    return;
  }
  if (printTechniqueListIfAsked(options.technique)) return;
  const SceneOverrides overrides = sceneOverrides(options.scene);
  const auto loadStart = std::chrono::steady_clock::now();
  Scene scene = loadScene(options.scene.scene);
  const double loadMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loadStart)
          .count();

  applyOverrides(scene, overrides);
  printSceneWarnings(scene);
  const std::vector<Technique> techniques = selectedTechniques(options.technique);
  gl::RenderSettings settings = toRenderSettings(options.render);
  settings.params = selectedParams(options.technique, techniques);

  checkOutputPath(options.outDir);  // before any GL work

  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  for (Technique technique : techniques) {
    settings.technique = technique;
    renderer.validate(settings);
  }
  std::cout << "loaded " << scene.name << ": " << scene.triangleCount() << " triangles in "
            << loadMs << " ms\n";
  // Only once every technique is known to fit, so that a refused request leaves no folder.
  namespace fs = std::filesystem;
  const fs::path dir = createOutputFolder(options.outDir);
  for (Technique technique : techniques) {
    settings.technique = technique;
    // Later repetitions time warm passes: shader JIT compilation lands in the first.
    gl::RenderResult result = renderer.render(scene, settings);
    for (int i = 1; i < options.repeat; ++i) result = renderer.render(scene, settings);
    const std::string stem = scene.name + "_" + std::string(techniqueId(technique));
    std::map<std::string, std::string> files{{"color", stem + ".png"},
                                             {"visibility_exr", stem + "_visibility.exr"},
                                             {"visibility_png", stem + "_visibility.png"},
                                             {"record", stem + ".json"}};
    const bool classified =
        technique == Technique::Esm && result.params.esm.classifier != shaders::kEsmClassifyNone;
    if (classified) {
      files["failure_mask"] = stem + "_failures.png";
      writeFailureMaskPng(result.diagnostic, result.color, dir / files.at("failure_mask"));
    }
    if (technique == Technique::Lvsm) {
      files["layers"] = stem + "_layers.png";
      writeLayerIndexPng(result.diagnostic, result.color, dir / files.at("layers"));
    }
    writeColorPng(result.color, dir / files.at("color"));
    writeFloatExr(result.visibility, dir / files.at("visibility_exr"));
    writeGrey16Png(result.visibility, dir / files.at("visibility_png"));
    std::ofstream json(dir / files.at("record"));
    json << gl::renderRecordJson(scene, settings, result, renderer.deviceDescription(), files);
    if (!json) throw Error("cannot write " + (dir / files.at("record")).string());
    std::cout << "wrote " << (dir / files.at("color")).string() << "  (GPU "
              << result.gpuTimes.total() << " ms, wall " << result.wallTimes.total()
              << " ms, technique memory "
              << double(result.memory.technique + result.memory.summedArea) / (1024.0 * 1024.0)
              << " MiB)\n";
  }
}

}  // namespace

void registerRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a built-in or glTF / OBJ scene with shadow-map techniques through OpenGL 4.5 (EGL).");
  addSceneOptions(*cmd, o->scene);
  addTechniqueOptions(*cmd, o->technique);
  addRenderOptions(*cmd, o->render);
  cmd->add_option("--repeat", o->repeat, "render N times and report the last (warm) timings")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("-o,--out", o->outDir, "output folder")->capture_default_str();
  cmd->callback([o] { runRender(*o); });
}

}  // namespace penumbra::cli
