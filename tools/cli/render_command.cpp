// `penumbra render`: parses options, calls penumbra::gl::Renderer, writes the images and record.
#include "render_command.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/render_record.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/image_io.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

struct RenderOptions {
  std::string scene = "backyard";
  TechniqueOptions technique{"evsm4", {}};
  int shadowSize = 2048;
  int msaa = 1;
  int blurTaps = 5;
  std::string blurKernel = "gaussian";
  float blurSigma = 0.0f;  // 0: half the radius, at least 0.5
  std::string filter = "trilinear";
  int aniso = 16;
  int width = 960;
  int height = 540;
  float normalOffset = 0.0f;
  std::string outDir = "out/render";
  int repeat = 1;
};

gl::RenderSettings toSettings(const RenderOptions& o) {
  gl::RenderSettings s;
  s.shadowMapSize = o.shadowSize;
  s.msaaSamples = o.msaa;
  if (o.blurTaps < 1 || o.blurTaps % 2 == 0) {
    throw Error("blur taps " + std::to_string(o.blurTaps) +
                ": give an odd kernel width (1 = no blur, 3, 5, 7, ... 129)");
  }
  s.blur.radius = (o.blurTaps - 1) / 2;
  if (o.blurKernel != "gaussian" && o.blurKernel != "box") {
    throw Error("unknown blur kernel '" + o.blurKernel + "'; valid kernels: gaussian, box");
  }
  s.blur.kernel = o.blurKernel == "box" ? BlurKernel::Box : BlurKernel::Gaussian;
  s.blur.sigma = o.blurSigma > 0.0f ? o.blurSigma : std::max(0.5f, 0.5f * float(s.blur.radius));
  s.filter = gl::parseFilterMode(o.filter);
  s.anisotropy = o.aniso;
  s.width = o.width;
  s.height = o.height;
  s.normalOffsetTexels = o.normalOffset;
  return s;
}

void runRender(const RenderOptions& options) {
  if (options.scene == "list") {
    for (std::string_view name : builtinSceneNames()) {
      std::cout << name << "  " << makeBuiltinScene(name).description << "\n";
    }
    return;
  }
  if (printTechniqueListIfAsked(options.technique)) return;
  const Scene scene = makeBuiltinScene(options.scene);
  const std::vector<Technique> techniques = selectedTechniques(options.technique);
  gl::RenderSettings settings = toSettings(options);
  settings.params = selectedParams(options.technique, techniques);

  namespace fs = std::filesystem;
  const fs::path dir = options.outDir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create output folder " + dir.string() + ": " + ec.message());

  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  for (Technique technique : techniques) {
    settings.technique = technique;
    renderer.validate(settings);
  }
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
    const bool classified = technique == Technique::Esm &&
                            result.params.esm.classifier != shaders::kEsmClassifyNone;
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
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render a built-in scene with shadow-map techniques through OpenGL 4.5 (EGL).");
  cmd->add_option("-s,--scene", o->scene, "built-in scene, or 'list'")->capture_default_str();
  addTechniqueOptions(*cmd, o->technique);
  cmd->add_option("--shadow-size", o->shadowSize, "shadow-map texels per side")->capture_default_str();
  cmd->add_option("--msaa", o->msaa, "light-pass samples: 1 (off), 2, 4, 8")->capture_default_str();
  cmd->add_option("--blur", o->blurTaps, "prefilter width in taps (odd; 1 = none); the summed-area "
                                         "filter's smallest box")->capture_default_str();
  cmd->add_option("--blur-kernel", o->blurKernel, "gaussian or box")->capture_default_str();
  cmd->add_option("--blur-sigma", o->blurSigma, "Gaussian sigma in texels (default: radius/2)");
  cmd->add_option("--filter", o->filter, "point, bilinear, trilinear, anisotropic or sat")
      ->capture_default_str();
  cmd->add_option("--aniso", o->aniso, "anisotropy for the anisotropic filter, 1..16")->capture_default_str();
  cmd->add_option("--width", o->width, "frame width in pixels")->capture_default_str();
  cmd->add_option("--height", o->height, "frame height in pixels")->capture_default_str();
  cmd->add_option("--normal-offset", o->normalOffset, "normal-offset bias in shadow-map texels")
      ->capture_default_str();
  cmd->add_option("--repeat", o->repeat, "render N times and report the last (warm) timings")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("-o,--out", o->outDir, "output folder")->capture_default_str();
  cmd->callback([o] { runRender(*o); });
}

}  // namespace penumbra::cli
