// The minimal kernels: a copy of the depth into every channel layer (beside encode), a plain
// separable blur of whole texels with the same taps (beside the prefilter), a plain tile blur of
// the depth in one dispatch (beside the fused prefilter), the driver's own mipmap generation
// (beside the mip pass), plain 64-bit prefix sums (beside the summed-area table), on textures like
// the channel texture, and the least lookup of the technique (beside the camera pass,
// Renderer::timeMinimalLookup).
#include "penumbra/gl/pass_bench.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "channel_dispatch.h"
#include "gl_formats.h"
#include "gpu_timer.h"
#include "memory_plan.h"
#include "minimal_copy.h"
#include "penumbra/error.h"
#include "penumbra/filters.h"
#include "penumbra/gl/context.h"
#include "penumbra/metrics.h"
#include "program_cache.h"

namespace penumbra::gl {
namespace {

Texture arrayTexture(unsigned format, int size, int layers, int levels) {
  Texture t(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(t.id(), levels, format, size, size, layers);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER,
                      levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
  return t;
}

// rawblur's values, (i mod 997) / 997: varied, so that no GPU reads them from a cleared
// texture's fast-clear compression, as no light pass's depth is.
std::vector<float> yardstickValues(size_t count) {
  std::vector<float> values(count);
  for (size_t i = 0; i < count; ++i) values[i] = float(i % 997) / 997.0f;
  return values;
}

// A minimal kernel and its times: timed once after each frame the renderer renders, so that load
// on the machine falls on the passes and their minimal kernels alike.
struct MinimalKernel {
  explicit MinimalKernel(std::function<void()> w) : work(std::move(w)) {}
  // A kernel that times itself (the minimal lookup times its draw, not its target's clear):
  // `measure` runs it and returns its milliseconds.
  explicit MinimalKernel(std::function<double()> m)
      : work([m] { (void)m(); }), measure(std::move(m)) {}
  std::function<void()> work;
  std::function<double()> measure;
  std::vector<double> times;
  void time(bool gpuTime) {
    if (measure) {
      times.push_back(measure());
      return;
    }
    GpuTimer timer;
    timer.begin();
    work();
    timer.end();
    times.push_back(timer.milliseconds(gpuTime));
  }
};

// The yardstick's kernels (../shared/yardsticks/rawblur.c, passes/yardstick_*.comp) on 2D
// textures of its float format with the layout's components, once per channel layer: its copy and
// its box blur of the same taps through a sampler. An independent check on the minimal kernels.
struct Yardstick {
  Yardstick(ProgramCache& programs, const ChannelLayout& layout, int texels, int radius)
      : layers(layout.layers),
        size(texels),
        format(layout.componentsPerTexel == 1   ? GL_R32F
               : layout.componentsPerTexel == 2 ? GL_RG32F
                                                : GL_RGBA32F),
        name(format == GL_R32F    ? "r32f"
             : format == GL_RG32F ? "rg32f"
                                  : "rgba32f") {
    for (Texture* t : {&source, &target}) {
      *t = Texture(GL_TEXTURE_2D);
      glTextureStorage2D(t->id(), 1, format, size, size);
    }
    // rawblur's values uploaded as RGBA (an R32F or RG32F texture keeps every fourth or every
    // other one: the timing does not depend on them).
    const std::vector<float> data = yardstickValues(size_t(size) * size_t(size) * 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(source.id(), 0, 0, 0, size, size, GL_RGBA, GL_FLOAT, data.data());
    const std::vector<ShaderDefine> defines{{"CHANNEL_FORMAT", name},
                                            {"RADIUS", std::to_string(radius)}};
    blurProgram = &programs.compute("passes/yardstick_blur.comp", defines);
    copyProgram = &programs.compute("passes/yardstick_copy.comp", defines);
  }
  void blurBothAxes() const {
    const GLint dir = glGetUniformLocation(blurProgram->id(), "dir");
    for (int layer = 0; layer < layers; ++layer) {
      glProgramUniform2i(blurProgram->id(), dir, 1, 0);
      glBindTextureUnit(0, source.id());
      glBindImageTexture(0, target.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
      blurProgram->dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
      glProgramUniform2i(blurProgram->id(), dir, 0, 1);
      glBindTextureUnit(0, target.id());
      glBindImageTexture(0, source.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
      blurProgram->dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
    }
  }
  void copy() const {
    for (int layer = 0; layer < layers; ++layer) {
      glBindTextureUnit(0, source.id());
      glBindImageTexture(0, target.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
      copyProgram->dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
    }
  }
  std::string describe(const std::string& what) const {
    return "rawblur " + what + ", " + name + (layers > 1 ? " x " + std::to_string(layers) : "");
  }

  int layers, size;
  unsigned format;
  std::string name;
  Texture source, target;
  const Program* blurProgram = nullptr;
  const Program* copyProgram = nullptr;
};

// The renderer's own pass times over `repeats` frames after a warm-up frame (shader compilation,
// resources), each frame followed by one timed run of every minimal kernel in `kernels`
// (warmed up too), its camera pass drawn kCameraDrawsPerFrame times in all, each draw followed
// by one timed run of every kernel in `lookups`, and, where `encodeKernels` are given, its
// encode dispatched kEncodeDispatchesPerFrame times in all, each dispatch after the frame's
// followed by one timed run of every kernel in `encodeKernels` (the frame's own by `kernels`).
// Times are GPU timer queries where they measure execution, else wall time between glFinish
// calls.
struct FramePasses {
  std::vector<double> encode, prefilter, mipsOrSat, camera;
};

FramePasses renderPasses(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                         int repeats, bool gpuTime, std::span<MinimalKernel* const> kernels,
                         std::span<MinimalKernel* const> lookups = {},
                         std::span<MinimalKernel* const> encodeKernels = {}) {
  FramePasses p;
  RenderSettings timed = settings;
  timed.readBack = frame_image::kNone;  // the times are all a repeat gives
  renderer.render(scene, timed);
  for (MinimalKernel* k : kernels) k->work();
  for (MinimalKernel* k : lookups) k->work();
  for (int i = 0; i < repeats; ++i) {
    const RenderResult r = renderer.render(scene, timed);
    const PassTimes& t = gpuTime ? r.gpuTimes.value() : r.wallTimes.value();
    p.encode.push_back(t.encode);
    p.prefilter.push_back(t.prefilter);
    p.mipsOrSat.push_back(t.mipsOrSat);
    p.camera.push_back(t.camera);
    for (MinimalKernel* k : kernels) k->time(gpuTime);
    if (!lookups.empty()) {
      for (int draw = 0; draw < kCameraDrawsPerFrame; ++draw) {
        if (draw > 0) p.camera.push_back(renderer.timeCameraPass());
        for (MinimalKernel* k : lookups) k->time(gpuTime);
      }
    }
    // After the camera draws, which read the prefiltered channels the dispatches overwrite.
    if (encodeKernels.empty()) continue;
    for (int dispatch = 1; dispatch < kEncodeDispatchesPerFrame; ++dispatch) {
      p.encode.push_back(renderer.timeEncodePass());
      for (MinimalKernel* k : encodeKernels) k->time(gpuTime);
    }
  }
  return p;
}

std::vector<double> sums(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> s(a.size());
  for (size_t i = 0; i < a.size(); ++i) s[i] = a[i] + b[i];
  return s;
}

// ESM that classifies its pixels (ESM paper §3.3) and shades the failing ones with its fallback:
// its camera pass also stands, with the classification off, beside the least lookup.
bool classifiesEsm(const RenderSettings& settings) {
  return settings.technique == Technique::Esm &&
         settings.params.esm.classifier != shaders::kEsmClassifyNone;
}

// ESM with the classifier the minimal lookup can run (the threshold test; Z-max reads a pyramid
// the yardstick does not build): its camera pass stands beside a lookup that classifies and
// falls back as it does.
bool hasFallbackYardstick(const RenderSettings& settings) {
  return classifiesEsm(settings) &&
         settings.params.esm.classifier == shaders::kEsmClassifyThreshold;
}

// What the camera pass's yardstick does (passes/minimal_lookup.frag): without (esmFallback
// false) or with ESM's classification and fallback.
std::string minimalLookupDescription(const RenderSettings& settings, bool summedArea,
                                     bool esmFallback) {
  if (summedArea) {
    return "minimal lookup: each channel's mean over the blur's box from the table, reconstruct, "
           "Lambert, RGBA8";
  }
  std::string reconstruct = "reconstruct";
  if (esmFallback) {
    reconstruct += settings.params.esm.fallback == shaders::kEsmFallbackPaper
                       ? " with the threshold test, and where it fails the paper's 2x2 fallback"
                       : " with the threshold test, and where it fails the pass's own PCF "
                         "fallback (the light's depth, a receiver plane from screen derivatives)";
  } else if (classifiesEsm(settings)) {
    reconstruct += " (no classification or fallback, which the pass has)";
  }
  return "minimal lookup: each layer filtered once, " + reconstruct + ", Lambert, RGBA8";
}

}  // namespace

FrameTimes frameTimes(const std::vector<double>& times) {
  if (times.empty()) return {};
  return {*std::min_element(times.begin(), times.end()), penumbra::median(times),
          int(times.size())};
}

std::string passSamplingDescription() {
  return "the camera pass drawn " + std::to_string(kCameraDrawsPerFrame) +
         " times a frame, each draw before its minimal lookup, and the separate encode "
         "dispatched " +
         std::to_string(kEncodeDispatchesPerFrame) + " times, each timed beside a run of its copy";
}

std::string passTimingDescription(const Renderer& renderer) {
  return renderer.timerQueriesMeasureExecution() ? "GPU timer queries"
                                                 : "wall clock (glFinish around each pass)";
}

void checkPassBenchable(const Scene& scene, const RenderSettings& settings) {
  if (settings.cascades.count != 1 || scene.light.kind == LightKind::Point) {
    throw Error(
        "bench --passes measures one map (--cascades 1, a directional or spot light): the "
        "minimal kernels run on one, where cascades and a point light's six faces are several");
  }
  if (scene.light.size > 0.0f) {
    throw Error(
        "bench --passes measures hard lights (--light-size 0): the minimal lookup has no "
        "blocker search or widened filter to stand beside a soft light's");
  }
}

PassBenchResult benchPasses(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                            int repeats) {
  if (repeats < 1 || repeats > 100) {
    throw Error("bench repeats " + std::to_string(repeats) + " is out of range [1, 100]");
  }
  if (!prefiltersChannels(settings.technique)) {
    throw Error(std::string(techniqueId(settings.technique)) +
                " has no prefilter passes to measure (it filters after the test)");
  }
  checkPassBenchable(scene, settings);
  const bool summedArea = settings.filter == FilterMode::SummedArea;
  const bool blurs = settings.blur.radius > 0 && !summedArea;
  const bool gpuTime = renderer.timerQueriesMeasureExecution();
  renderer.setScene(scene);
  RenderSettings separate = settings;
  separate.fusePrefilter = false;
  renderer.render(scene, separate);  // the channel texture's mip levels, for the kernels' textures

  const ChannelLayout layout = channelLayout(settings.technique, settings.params);
  const unsigned format = internalFormat(layout);
  const int size = settings.shadowMapSize;
  const int levels = renderer.channelMipLevels();
  ProgramCache programs;
  const std::vector<ShaderDefine> defines = formatDefines(layout);
  // The yardstick's values as depths.
  Texture depth = arrayTexture(GL_R32F, size, 1, 1);
  const std::vector<float> depths = yardstickValues(size_t(size) * size_t(size));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage3D(depth.id(), 0, 0, 0, 0, size, size, 1, GL_RED, GL_FLOAT, depths.data());
  Texture channels = arrayTexture(format, size, layout.layers, levels);
  Texture scratch = arrayTexture(format, size, layout.layers, 1);

  const MinimalCopy copyKernel(programs, layout, size);
  MinimalKernel copy{[&] { copyKernel.run(depth, channels); }};

  std::vector<ShaderDefine> blurDefines = defines;
  for (ShaderDefine& d : blurKernelDefines(settings.blur)) blurDefines.push_back(std::move(d));
  const Program& blurProgram = programs.compute("passes/baseline_blur.comp", blurDefines);
  setSize(blurProgram, "size", size);
  const GLint direction = glGetUniformLocation(blurProgram.id(), "direction");
  MinimalKernel blur{[&] {
    for (int layer = 0; layer < layout.layers; ++layer) {
      bindChannelLayer(1, channels, layout, layer, GL_READ_ONLY);
      bindChannelLayer(0, scratch, layout, layer, GL_WRITE_ONLY);
      glProgramUniform2i(blurProgram.id(), direction, 1, 0);
      blurProgram.dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
      bindChannelLayer(1, scratch, layout, layer, GL_READ_ONLY);
      bindChannelLayer(0, channels, layout, layer, GL_WRITE_ONLY);
      glProgramUniform2i(blurProgram.id(), direction, 0, 1);
      blurProgram.dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
    }
  }};

  // The fused prefilter's minimal kernel: the copy and both axes in one dispatch of its tiles.
  std::vector<ShaderDefine> fusedDefines = blurDefines;
  for (ShaderDefine& d : fusedTileDefines(layout)) fusedDefines.push_back(std::move(d));
  const Program& fusedProgram = programs.compute("passes/baseline_fused.comp", fusedDefines);
  setSize(fusedProgram, "size", size);
  MinimalKernel fusedBlur{[&] {
    glBindTextureUnit(0, depth.id());
    bindChannelImage(channels, layout, 0);
    fusedProgram.dispatch(groups(size, kFusedTile), groups(size, kFusedTile),
                          unsigned(layout.layers));
  }};

  Yardstick yardstick(programs, layout, size, settings.blur.radius);

  MinimalKernel generateMips{[&] { glGenerateTextureMipmap(channels.id()); }};

  const int channelCount = layout.channels;
  std::optional<Buffer> prefixSums;  // as large as the table: only when it is measured
  if (summedArea) prefixSums.emplace(summedAreaSizes(channelCount, size).sums);
  const Program& rows = programs.compute("passes/baseline_prefix_sums.comp", {{"AXIS", "0"}});
  const Program& columns = programs.compute("passes/baseline_prefix_sums.comp", {{"AXIS", "1"}});
  for (const Program* p : {&rows, &columns}) {
    setSize(*p, "size", size);
    p->set("channelCount", channelCount);
    p->set("layersPerCascade", layout.layers);
  }
  MinimalKernel prefix{[&] {
    glBindTextureUnit(0, channels.id());
    prefixSums->bindStorage(3);
    rows.dispatch(groups(size, 64), unsigned(channelCount));
    columns.dispatch(groups(size, 64), unsigned(channelCount));
  }};

  // After each frame, the same view drawn with the least lookup of the technique, or ESM's with
  // its classification and fallback.
  const bool esmFallback = hasFallbackYardstick(settings);
  MinimalKernel cameraYardstick{
      std::function<double()>([&] { return renderer.timeMinimalLookup(esmFallback); })};

  MinimalKernel yardstickCopy{[&] { yardstick.copy(); }};
  MinimalKernel yardstickBlur{[&] { yardstick.blurBothAxes(); }};
  std::vector<MinimalKernel*> beside{&copy, &yardstickCopy};
  if (blurs) beside.insert(beside.end(), {&blur, &yardstickBlur});
  if (summedArea) beside.push_back(&prefix);
  if (!summedArea && levels > 1) beside.push_back(&generateMips);
  const std::vector<MinimalKernel*> lookups{&cameraYardstick};
  // The yardstick's copy, informative, stays at one run a frame.
  const std::vector<MinimalKernel*> encodeBeside{&copy};
  const FramePasses passes =
      renderPasses(renderer, scene, separate, repeats, gpuTime, beside, lookups, encodeBeside);

  PassBenchResult result;
  result.technique = settings.technique;
  result.timing = passTimingDescription(renderer);
  result.format = imageFormatQualifier(layout) + " x " + std::to_string(layout.layers) +
                  (layout.layers == 1 ? " layer" : " layers");
  result.passes.push_back({"encode", frameTimes(passes.encode), "copy depth to every layer",
                           frameTimes(copy.times), yardstick.describe("copy"),
                           frameTimes(yardstickCopy.times)});
  const std::string taps = std::to_string(2 * settings.blur.radius + 1) + " taps";
  if (blurs) {
    result.passes.push_back({"prefilter", frameTimes(passes.prefilter),
                             "plain separable blur, " + taps, frameTimes(blur.times),
                             yardstick.describe("blur, " + taps), frameTimes(yardstickBlur.times)});
  }
  if (summedArea) {
    result.passes.push_back({"summed-area table",
                             frameTimes(passes.mipsOrSat),
                             "plain 64-bit row and column prefix sums",
                             frameTimes(prefix.times),
                             "",
                             {}});
  } else if (levels > 1) {
    result.passes.push_back({"mips",
                             frameTimes(passes.mipsOrSat),
                             "glGenerateTextureMipmap",
                             frameTimes(generateMips.times),
                             "",
                             {}});
  }
  result.passes.push_back({"camera",
                           frameTimes(passes.camera),
                           minimalLookupDescription(settings, summedArea, esmFallback),
                           frameTimes(cameraYardstick.times),
                           "",
                           {}});
  // The fused path, where the settings allow it, whichever the caller chose (it is off by default).
  RenderSettings fusedSettings = settings;
  fusedSettings.fusePrefilter = true;
  if (fusesPrefilter(fusedSettings, settings.blur.radius)) {
    // The fused dispatch does both passes' work in one: it stands beside the plain fused kernel
    // of the same traffic, and the yardstick's copy and blur, timed after each of its own frames.
    for (MinimalKernel* k : {&yardstickCopy, &yardstickBlur}) k->times.clear();
    const std::vector<MinimalKernel*> both{&fusedBlur, &yardstickCopy, &yardstickBlur};
    const FramePasses fused = renderPasses(renderer, scene, fusedSettings, repeats, gpuTime, both);
    result.passes.push_back({"encode + prefilter, fused",
                             frameTimes(sums(fused.encode, fused.prefilter)),
                             "plain fused tile blur of depth, " + taps, frameTimes(fusedBlur.times),
                             yardstick.describe("copy + blur, " + taps),
                             frameTimes(sums(yardstickCopy.times, yardstickBlur.times))});
  }
  if (classifiesEsm(settings)) {
    // ESM's camera pass with the classification off beside the least lookup, in frames of their
    // own (the classification is compiled into the pass, lookupParameterDefines); run last, so
    // that the pass's and the yardstick's targets show what they drew; listed after "camera".
    RenderSettings unclassified = separate;
    unclassified.params.esm.classifier = shaders::kEsmClassifyNone;
    MinimalKernel leastLookup{
        std::function<double()>([&] { return renderer.timeMinimalLookup(false); })};
    const std::vector<MinimalKernel*> least{&leastLookup};
    const FramePasses plain =
        renderPasses(renderer, scene, unclassified, repeats, gpuTime, {}, least);
    const auto camera = std::ranges::find(result.passes, "camera", &PassTiming::pass);
    result.passes.insert(camera + 1, {"camera, classification off",
                                      frameTimes(plain.camera),
                                      minimalLookupDescription(unclassified, summedArea, false),
                                      frameTimes(leastLookup.times),
                                      "",
                                      {}});
  }
  checkErrors("bench --passes");
  return result;
}

}  // namespace penumbra::gl
