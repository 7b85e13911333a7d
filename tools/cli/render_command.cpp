// `penumbra render`: parses options, calls penumbra::gl::Renderer, writes the images and record.
#include "render_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "interrupt_cleanup.h"
#include "output_folder.h"
#include "penumbra/animation.h"
#include "penumbra/compare/shadowed_frame.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/render_record.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/gl/settings_json.h"
#include "penumbra/image_io.h"
#include "penumbra/metrics.h"
#include "penumbra/output_journal.h"
#include "penumbra/run_program.h"
#include "penumbra/text_file.h"
#include "render_options.h"
#include "scene_options.h"
#include "settings_options.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

struct RenderCommandOptions {
  SceneOptions scene;
  TechniqueOptions technique{"evsm4", {}};
  RenderOptions render;
  OutputOptions output{"out/render"};
  int repeat = 1;
  int frames = 1;
  std::vector<std::string> animate;  // empty: defaultAnimations
  std::string settingsFile;
  const CLI::App* command = nullptr;  // to tell options given explicitly from defaults
};

// --frames encodes with Debian's ffmpeg: found missing before anything is rendered.
void requireFfmpeg() {
  if (!runProgram({"ffmpeg", "-loglevel", "quiet", "-version"}).succeeded()) {
    throw Error(
        "--frames encodes an MP4 with ffmpeg, which was not found on PATH "
        "(scripts/install-deps installs Debian's ffmpeg)");
  }
}

// Writes frames/<stem>_NNNN.png for each frame of the animation and encodes <stem>.mp4 with
// ffmpeg (H.264, yuv420p: plays everywhere). Returns the last frame's result.
gl::RenderResult renderSequence(gl::Renderer& renderer, Scene& scene,
                                const gl::RenderSettings& settings,
                                const RenderCommandOptions& options,
                                const std::filesystem::path& dir, const std::string& stem,
                                std::map<std::string, std::string>& files) {
  std::vector<Animation> animations;
  for (const std::string& name : options.animate) animations.push_back(parseAnimation(name));
  if (animations.empty()) animations = defaultAnimations(scene);
  const bool clip =
      std::find(animations.begin(), animations.end(), Animation::Clip) != animations.end();
  namespace fs = std::filesystem;
  createOutputDirectory(dir / "frames");
  gl::RenderResult result;
  for (int frame = 0; frame < options.frames; ++frame) {
    const AnimatedView view = animatedView(scene, animations, frame, options.frames);
    if (clip) {
      poseScene(scene, clipTime(scene, frame));
      renderer.setScene(scene);  // the new pose's vertices
    }
    result = renderer.render(settings, gl::FrameView{view.camera, view.light});
    char name[32];
    std::snprintf(name, sizeof name, "_%04d.png", frame);
    writeColorPng(result.color, dir / "frames" / (stem + name));
  }
  if (clip) {
    poseScene(scene, 0.0f);  // the next technique starts from the clip's start again
    renderer.setScene(scene);
  }
  files["frames"] = "frames/" + stem + "_%04d.png";
  files["video"] = stem + ".mp4";
  // Absolute paths: ffmpeg reads a leading "name:" as a protocol (concat:, subfile:, ...). The
  // input is a pattern: a '%' of the folder's or the scene's name is doubled to stay literal.
  const fs::path absoluteDir = fs::absolute(dir);
  std::string pattern = (absoluteDir / "frames" / stem).string();
  for (size_t at = pattern.find('%'); at != std::string::npos; at = pattern.find('%', at + 2)) {
    pattern.insert(at, 1, '%');
  }
  const std::vector<std::string> command{
      "ffmpeg", "-nostdin", "-y", "-loglevel", "error", "-framerate", "30", "-i",
      pattern + "_%04d.png", "-c:v", "libx264", "-pix_fmt", "yuv420p",
      // H.264 in yuv420p needs even sizes.
      "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", (absoluteDir / files.at("video")).string()};
  recordOutput(dir / files.at("video"));
  if (!runProgram(command).succeeded()) {
    throw Error("ffmpeg could not encode " + files.at("video") +
                " (is Debian's ffmpeg installed? scripts/install-deps installs it)");
  }
  return result;
}

void runRender(const RenderCommandOptions& options) {
  if (options.scene.scene == "list") {
    for (std::string_view name : builtinSceneNames()) {
      std::cout << name << "  " << makeBuiltinScene(name).description << "\n";
    }
    return;
  }
  if (printTechniqueListIfAsked(options.technique)) return;
  const gl::Settings resolved = resolveSettings(*options.command, options.settingsFile,
                                                options.scene, options.technique, options.render);
  const SceneOverrides& overrides = resolved.view;
  const auto loadStart = std::chrono::steady_clock::now();
  const float aspect = float(resolved.render.width) / float(resolved.render.height);
  if (printCameraListIfAsked(options.scene, resolved.scene, aspect)) return;
  Scene scene = loadScene(resolved.scene, sceneLoadOptions(options.scene, resolved));
  const double loadMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loadStart)
          .count();

  applyOverrides(scene, overrides);
  printSceneWarnings(scene);
  const std::vector<Technique>& techniques = resolved.techniques;
  if (const std::string w = translucencyWarning(scene, techniques); !w.empty()) {
    std::cerr << "penumbra: warning: " << w << "\n";
  }
  for (const std::string& name : options.animate) {  // before any GL work
    if (parseAnimation(name) == Animation::Clip && !scene.animation.moves()) {
      throw Error("--animate clip plays a scene file's own animation; scene '" + scene.name +
                  "' has none (" + animationNameList() + ")");
    }
  }
  if (options.frames > 1) requireFfmpeg();
  gl::RenderSettings settings = resolved.render;
  settings.lookupInputs = true;  // the mostly-shadowed warning reads the lit surfaces
  requireCascadableLight(settings.cascades, scene.light);

  CommandOutput output(options.output);  // before any GL work
  InterruptCleanup interrupt;  // before the GL context: its driver threads inherit the mask
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
  const fs::path dir = output.begin(interrupt);
  std::vector<std::string> summaries;
  double leastShadowed = 1.0;  // over the techniques: the frame is mostly shadowed for all
  for (Technique technique : techniques) {
    settings.technique = technique;
    const std::string stem = scene.name + "_" + std::string(techniqueId(technique));
    std::map<std::string, std::string> files{{"color", stem + ".png"},
                                             {"visibility_exr", stem + "_visibility.exr"},
                                             {"visibility_png", stem + "_visibility.png"},
                                             {"record", stem + ".json"},
                                             {"settings", stem + "_settings.json"}};
    // Later repetitions time warm passes: shader JIT compilation lands in the first.
    renderer.setScene(scene);
    gl::RenderResult result = renderer.render(scene, settings);
    for (int i = 1; i < options.repeat; ++i) result = renderer.render(scene, settings);
    if (options.frames > 1) {
      result = renderSequence(renderer, scene, settings, options, dir, stem, files);
    }
    leastShadowed = std::min(
        leastShadowed, compare::shadowedShare(result.visibility, litSurfaceMask(result.lookup)));
    const bool classified =
        technique == Technique::Esm && result.params.esm.classifier != shaders::kEsmClassifyNone;
    if (classified) {
      files["failure_mask"] = stem + "_failures.png";
      writeFailureMaskPng(result.diagnostic, result.color, dir / files.at("failure_mask"));
    }
    if (technique == Technique::Lvsm || technique == Technique::PowerCdf) {
      files["layers"] = stem + "_layers.png";
      writeLayerIndexPng(result.diagnostic, result.color, dir / files.at("layers"));
    }
    writeColorPng(result.color, dir / files.at("color"));
    writeFloatExr(result.visibility, dir / files.at("visibility_exr"));
    writeGrey16Png(result.visibility, dir / files.at("visibility_png"));
    writeTextFile(
        dir / files.at("record"),
        gl::renderRecordJson(scene, settings, result, renderer.deviceDescription(), files));
    // The picture again through --settings: this technique, these settings, this exact view.
    gl::Settings again = resolved;
    again.techniques = {technique};
    again.render = settings;
    again.view = viewOverrides(scene);
    writeTextFile(dir / files.at("settings"), gl::settingsJson(again));
    std::ostringstream summary;
    summary << "wrote " << (output.target() / files.at("color")).string() << "  (";
    if (result.gpuTimes) summary << "GPU " << result.gpuTimes->total() << " ms, ";
    summary << "wall " << result.wallTimes.value().total() << " ms, technique memory "
            << double(result.memory.technique + result.memory.summedArea) / (1024.0 * 1024.0)
            << " MiB)";
    summaries.push_back(summary.str());
  }
  output.finish(interrupt);
  for (const std::string& line : summaries) std::cout << line << "\n";
  if (const auto warning = compare::mostlyShadowedWarning(scene, leastShadowed)) {
    std::cout << "warning: " << *warning << "\n";
  }
}

}  // namespace

void registerRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a built-in or glTF / OBJ scene with shadow-map techniques through OpenGL 4.5 (EGL). "
      "Its defaults make pictures (the values below); compare's measure (480x270, 1024, box, "
      "bilinear: compare --help says why), so their images of a scene differ unless given the "
      "same values.");
  addSceneOptions(*cmd, o->scene);
  addTechniqueOptions(*cmd, o->technique);
  addRenderOptions(*cmd, o->render);
  addSettingsOption(*cmd, o->settingsFile);
  o->command = cmd;
  cmd->add_option("--repeat", o->repeat, "render N times and report the last (warm) timings")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  CLI::Option* frames =
      cmd->add_option("--frames", o->frames,
                      "render an animated sequence of N frames into frames/ and an MP4 (ffmpeg)")
          ->check(CLI::Range(1, 10000))
          ->capture_default_str();
  cmd->add_option("--animate", o->animate,
                  "animations for --frames: " + animationNameList() +
                      " (comma-separated; clip plays a scene file's own animation at 30 frames "
                      "a second, looped; default: clip where the scene has one, else orbit)")
      ->needs(frames)
      ->delimiter(',')
      ->capture_default_str();
  addOutputOptions(*cmd, o->output, "the images, visibility and records");
  cmd->callback([o] { runRender(*o); });
}

}  // namespace penumbra::cli
