// The renderer: settings validation, light pass, camera pass, read-backs and measurements.
#include "penumbra/gl/renderer.h"

#include <epoxy/gl.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <iomanip>
#include <sstream>

#include "gl_formats.h"
#include "gpu_scene.h"
#include "memory_plan.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/params.h"
#include "penumbra/shadow_lookup.h"
#include "renderer_state.h"
#include "shared/shading.h"
#include "shared/summed_area.h"

namespace penumbra::gl {
namespace {

std::string formatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// Settings hold floats: compared in float, a documented bound (0.01 is 0.00999999978f) is itself
// accepted and one float step beyond it is not.
void checkRange(std::string_view what, float value, float lo, float hi) {
  if (!(value >= lo && value <= hi)) {
    throw Error(std::string(what) + " " + formatNumber(value) + " is out of range [" +
                formatNumber(lo) + ", " + formatNumber(hi) + "]");
  }
}

void checkRange(std::string_view what, int value, int lo, int hi) {
  if (value < lo || value > hi) {
    throw Error(std::string(what) + " " + std::to_string(value) + " is out of range [" +
                std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
}

// Copies a GL image (row 0 at the bottom) into an Image, optionally flipping to row 0 at the top.
Image readTexture(unsigned texture, int level, int width, int height, int layers, int components,
                  GLenum format, bool flip) {
  std::vector<float> data(size_t(width) * size_t(height) * size_t(layers) * size_t(components));
  glGetTextureImage(texture, level, format, GL_FLOAT, GLsizei(data.size() * sizeof(float)),
                    data.data());
  checkErrors("reading back a texture");
  Image image(width, height, layers * components);
  for (int layer = 0; layer < layers; ++layer) {
    for (int y = 0; y < height; ++y) {
      const int row = flip ? height - 1 - y : y;
      for (int x = 0; x < width; ++x) {
        for (int c = 0; c < components; ++c) {
          image.at(x, row, layer * components + c) =
              data[((size_t(layer) * size_t(height) + size_t(y)) * size_t(width) + size_t(x)) *
                       size_t(components) +
                   size_t(c)];
        }
      }
    }
  }
  return image;
}

// 1 + 3/4 of an fp16 step at 1: rounding to nearest stores 1 + 2^-10, truncation stores 1.
HalfRounding probeHalfRounding(Renderer::State& s) {
  const float value = 1.0f + 3.0f / 4096.0f;
  Texture target(GL_TEXTURE_2D);
  glTextureStorage2D(target.id(), 1, GL_RGBA16F, 1, 1);
  const Program& probe = s.compute("passes/half_rounding_probe.comp", {});
  probe.set("value", value);
  glBindImageTexture(0, target.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  probe.dispatch(1);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  float stored[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glGetTextureImage(target.id(), 0, GL_RGBA, GL_FLOAT, sizeof stored, stored);
  checkErrors("probing fp16 rounding");
  return stored[0] < value ? HalfRounding::TowardZero : HalfRounding::Nearest;
}

// The bytes actually allocated now, from the live objects' sizes.
MemoryReport memoryReport(const Renderer::State& s) {
  const RenderSettings& settings = s.settings;
  MemoryReport m;
  m.lightPass = lightPassBytes(s.shadowMapSize, s.msaaSamples);
  m.technique =
      channelTextureBytes(s.layout, s.shadowMapSize, s.shadowMapSize, s.channelLevels > 1);
  if (s.satSums) m.summedArea = s.satSums->size() + s.satStats->size() + s.satRows->size();
  if (s.scratch.id() != 0)
    m.scratch = channelTextureBytes(s.layout, s.shadowMapSize, s.shadowMapSize, false);
  if (s.zmax.id() != 0) {
    const ChannelLayout r32f{1, 1, 1, StorageFormat::Float32};
    m.auxiliary += channelTextureBytes(r32f, s.shadowMapSize, s.shadowMapSize, true);
  }
  if (s.splitSamples) m.auxiliary += s.splitSamples->size();
  m.frame = frameBytes(settings.width, settings.height);
  return m;
}

std::string gib(uint64_t bytes) {
  std::ostringstream out;
  out << std::setprecision(3) << double(bytes) / double(uint64_t(1) << 30) << " GiB";
  return out.str();
}

// What the GL can give one render, and where that figure comes from.
struct MemoryBudget {
  uint64_t bytes = 0;
  std::string source;
};

MemoryBudget glMemoryBudget(const Renderer::State& s) {
  // The vendor queries report free memory, which excludes what this renderer holds now and
  // frees or reuses for the next render.
  const uint64_t held = s.lightFramebuffer != 0 ? memoryReport(s).total() : 0;
  if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
    GLint kib = 0;
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &kib);
    const uint64_t free = uint64_t(kib) * 1024 + held;
    return {free, "the " + gib(free) + " of GPU memory free (GL_NVX_gpu_memory_info)"};
  }
  if (epoxy_has_gl_extension("GL_ATI_meminfo")) {
    GLint kib[4] = {};
    glGetIntegerv(GL_TEXTURE_FREE_MEMORY_ATI, kib);
    const uint64_t free = uint64_t(kib[0]) * 1024 + held;
    return {free, "the " + gib(free) + " of texture memory free (GL_ATI_meminfo)"};
  }
  // llvmpipe and GLs that do not say: textures live in RAM beside the read-backs and reports.
  const uint64_t ram = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  return {ram / 2, "the budget of " + gib(ram / 2) + ", half of this machine's " + gib(ram) +
                       " of RAM (this GL does not report its memory)"};
}

MemoryBudget memoryBudget(const Renderer::State& s) {
  const MemoryBudget offered = glMemoryBudget(s);
  if (s.memoryLimit == 0 || s.memoryLimit >= offered.bytes) return offered;
  return {s.memoryLimit, "the limit of " + gib(s.memoryLimit) + " (" +
                             std::to_string(s.memoryLimit) + " bytes) set on the renderer"};
}

// The GL's own answer to "could this texture be created?" (proxy targets, GL 4.5 §8.22).
bool proxyAccepts(const PlannedTexture& t) {
  if (t.proxyTarget == GL_PROXY_TEXTURE_2D_MULTISAMPLE) {
    // Mesa takes multisample proxies only through TexImage (TexStorage wants a bound object).
    glTexImage2DMultisample(t.proxyTarget, t.samples, t.internalFormat, t.width, t.height, GL_TRUE);
  } else if (t.proxyTarget == GL_PROXY_TEXTURE_2D_ARRAY) {
    glTexStorage3D(t.proxyTarget, t.levels, t.internalFormat, t.width, t.height, t.layers);
  } else {
    glTexStorage2D(t.proxyTarget, t.levels, t.internalFormat, t.width, t.height);
  }
  GLint width = 0;
  glGetTexLevelParameteriv(t.proxyTarget, 0, GL_TEXTURE_WIDTH, &width);
  return width != 0;
}

// Why these settings do not fit, or nothing when they do.
std::string memoryShortfall(const RenderSettings& settings, const MemoryBudget& budget,
                            int maxArrayLayers) {
  for (const PlannedTexture& t : plannedTextures(settings)) {
    if (t.layers > maxArrayLayers) {
      return "its " + std::string(t.what) + " needs " + std::to_string(t.layers) +
             " array layers, more than this GL's " + std::to_string(maxArrayLayers);
    }
    if (!proxyAccepts(t)) {
      return "this GL cannot create its " + std::to_string(t.width) + "x" +
             std::to_string(t.height) + " " + std::string(t.what) + " of " + gib(t.bytes) +
             " (GL proxy test)";
    }
  }
  if (estimateMemory(settings).total() > budget.bytes) return "that is more than " + budget.source;
  return {};
}

}  // namespace

Renderer::State::~State() {
  if (lightFramebuffer != 0) glDeleteFramebuffers(1, &lightFramebuffer);
  if (frameFramebuffer != 0) glDeleteFramebuffers(1, &frameFramebuffer);
}

namespace {

// Every variant is specialised to the current technique (TECHNIQUE_ID).
std::vector<ShaderDefine> withTechnique(const RenderSettings& settings,
                                        std::vector<ShaderDefine> defines) {
  defines.push_back({"TECHNIQUE_ID", std::to_string(int(settings.technique))});
  return defines;
}

std::string variantKey(std::string key, const std::vector<ShaderDefine>& defines) {
  for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
  return key;
}

}  // namespace

const Program& Renderer::State::graphics(const std::string& vertex, const std::string& fragment,
                                         const std::vector<ShaderDefine>& defines) {
  const std::vector<ShaderDefine> all = withTechnique(settings, defines);
  const std::string key = variantKey(vertex + "|" + fragment, all);
  auto found = programs.find(key);
  if (found == programs.end()) {
    found = programs.emplace(key, Program::graphics(library, vertex, fragment, all)).first;
  }
  return found->second;
}

const Program& Renderer::State::compute(const std::string& path,
                                        const std::vector<ShaderDefine>& defines) {
  const std::vector<ShaderDefine> all = withTechnique(settings, defines);
  const std::string key = variantKey(path, all);
  auto found = programs.find(key);
  if (found == programs.end()) {
    found = programs.emplace(key, Program::compute(library, path, all)).first;
  }
  return found->second;
}

void Renderer::State::bindParameters() const {
  paramsBlock->bindUniform(0);
}

void Renderer::State::uploadParameters() {
  glNamedBufferSubData(paramsBlock->id(), 0, sizeof(TechniqueParams), &params);
}

Renderer::Renderer(const HeadlessContext& context) : state_(std::make_unique<State>()) {
  state_->device = context.description();
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &state_->maxTextureSize);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &state_->maxArrayLayers);
  GLint colorSamples = 0, depthSamples = 0;
  glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &colorSamples);
  glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &depthSamples);
  state_->maxSamples = std::min(colorSamples, depthSamples);
  glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &state_->maxAnisotropy);
  state_->paramsBlock.emplace(sizeof(TechniqueParams));
  state_->halfRounding = probeHalfRounding(*state_);
  checkErrors("creating the renderer");
}

HalfRounding Renderer::halfFloatRounding() const {
  return state_->halfRounding;
}

Renderer::~Renderer() = default;

void Renderer::limitMemory(uint64_t bytes) {
  state_->memoryLimit = bytes;
}

std::string Renderer::deviceDescription() const {
  return state_->device;
}

void Renderer::validate(const RenderSettings& settings) const {
  const State& s = *state_;
  checkRange("shadow-map size", settings.shadowMapSize, 16, s.maxTextureSize);
  checkRange("frame width", settings.width, 1, s.maxTextureSize);
  checkRange("frame height", settings.height, 1, s.maxTextureSize);
  if (settings.msaaSamples != 1 && settings.msaaSamples != 2 && settings.msaaSamples != 4 &&
      settings.msaaSamples != 8) {
    throw Error("MSAA samples " + std::to_string(settings.msaaSamples) +
                ": valid values are 1 (off), 2, 4, 8");
  }
  if (settings.msaaSamples > s.maxSamples) {
    throw Error("MSAA samples " + std::to_string(settings.msaaSamples) + ": this GL (" + s.device +
                ") supports at most " + std::to_string(s.maxSamples));
  }
  checkRange("blur radius", settings.blur.radius, 0, shaders::kMaxBlurRadius);
  checkRange("blur sigma", settings.blur.sigma, 0.01f, 64.0f);
  checkRange("anisotropy", settings.anisotropy, 1, std::min(16, int(s.maxAnisotropy)));
  checkRange("normal offset (texels)", settings.normalOffsetTexels, 0.0f, 10.0f);
  checkRange("ambient", settings.ambient, 0.0f, 1.0f);
  validateParams(settings.technique, settings.params);
  if (settings.filter == FilterMode::SummedArea &&
      (settings.technique == Technique::Evsm2 || settings.technique == Technique::Evsm4 ||
       settings.technique == Technique::Esm)) {
    // Fixed-point sums bound the error by the channel's largest deviation (R * 2^-32): exponential
    // channels span up to e^+-84, so every small value would drown.
    throw Error("the summed-area filter sums channels in fixed point relative to their range; " +
                std::string(techniqueId(settings.technique)) +
                "'s exponential channels span too many orders of magnitude; use vsm, lvsm, csm or "
                "msm with sat, or trilinear/anisotropic for this technique");
  }
  if (settings.filter == FilterMode::SummedArea) {
    const TechniqueParams& p = settings.params;
    for (int c = 0; c < channelCount(settings.technique, p); ++c) {
      if (channelReduction(settings.technique, p, c) != ChannelReduction::Mean) {
        throw Error(
            "the summed-area filter averages channels, but " +
            std::string(techniqueId(settings.technique)) +
            " has min/max or log-space channels; use point, bilinear, trilinear or anisotropic");
      }
    }
    // The table is one storage buffer of channels x size^2 64-bit sums, indexed in 32 bits.
    const uint64_t entries = uint64_t(channelCount(settings.technique, p)) *
                             uint64_t(settings.shadowMapSize) * uint64_t(settings.shadowMapSize);
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    if (entries >= (uint64_t(1) << 32) || entries * 8 > uint64_t(maxBlock)) {
      throw Error("the summed-area table of " + std::string(techniqueId(settings.technique)) +
                  " at " + std::to_string(settings.shadowMapSize) + "^2 needs " +
                  std::to_string(entries * 8) + " bytes in one storage buffer; this GL holds " +
                  std::to_string(maxBlock) + "; use a smaller shadow map");
    }
  }
  checkMemory(settings);
}

void Renderer::checkMemory(const RenderSettings& settings) const {
  const State& s = *state_;
  const MemoryBudget budget = memoryBudget(s);
  const std::string shortfall = memoryShortfall(settings, budget, s.maxArrayLayers);
  if (shortfall.empty()) return;
  // The largest shadow-map size that fits with everything else unchanged (all allocations grow
  // with it, so the search is monotone).
  auto fits = [&](int size) {
    RenderSettings smaller = settings;
    smaller.shadowMapSize = size;
    return memoryShortfall(smaller, budget, s.maxArrayLayers).empty();
  };
  std::string advice = "no shadow-map size fits with this frame size";
  if (fits(16)) {
    int lo = 16, hi = settings.shadowMapSize;  // fits(lo), !fits(hi)
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (fits(mid) ? lo : hi) = mid;
    }
    advice = "the largest shadow-map size that fits is " + std::to_string(lo);
  }
  const uint64_t need = estimateMemory(settings).total();
  throw Error(std::string(techniqueId(settings.technique)) + " at shadow-map size " +
              std::to_string(settings.shadowMapSize) + " (frame " + std::to_string(settings.width) +
              "x" + std::to_string(settings.height) +
              (settings.msaaSamples > 1 ? ", " + std::to_string(settings.msaaSamples) + "x MSAA"
                                        : std::string()) +
              ") needs " + gib(need) + " (" + std::to_string(need) + " bytes), and " + shortfall +
              "; " + advice);
}

RenderResult Renderer::render(const Scene& scene, const RenderSettings& settings) {
  validate(settings);
  State& s = *state_;
  s.settings = settings;
  s.params = settings.params;
  if (settings.technique == Technique::Lvsm &&
      s.params.lvsm.placement == shaders::kLayerPlacementUniform) {
    s.params.lvsm.splits = shaders::uniformLayerSplits(s.params.lvsm.splits.layerCount);
  }
  s.uploadParameters();
  s.zmax = Texture();
  s.zmaxLevels = 0;
  s.splitSamples.reset();
  if (s.shadowMapSize != settings.shadowMapSize || s.msaaSamples != settings.msaaSamples ||
      s.lightFramebuffer == 0) {
    s.shadowMapSize = settings.shadowMapSize;
    s.msaaSamples = settings.msaaSamples;
    allocateLightPass(s);
  }
  allocateChannels(s, settings);
  allocateFrame(s, settings.width, settings.height);
  const GpuScene gpuScene(scene);
  const LightView light = fitLightView(scene);

  renderLightPass(s, gpuScene, light);
  s.auxiliaryTimer.begin();
  if (buildsZmaxPyramid(settings)) buildZmaxPyramid(s, s.lightDepth.id(), s.msaaSamples > 1);
  if (placesLayersByLloyd(settings)) {
    placeLayersByLloyd(s, s.lightDepth.id(), s.msaaSamples > 1);
    s.uploadParameters();
  }
  s.auxiliaryTimer.end();
  encodeChannels(s, s.lightDepth.id(), s.msaaSamples > 1);
  prefilterChannels(s);
  renderCameraPass(s, scene, gpuScene, light);

  RenderResult result;
  result.color =
      readTexture(s.frameColor.id(), 0, settings.width, settings.height, 1, 4, GL_RGBA, true);
  result.visibility =
      readTexture(s.frameVisibility.id(), 0, settings.width, settings.height, 1, 1, GL_RED, true);
  result.diagnostic =
      readTexture(s.frameDiagnostic.id(), 0, settings.width, settings.height, 1, 1, GL_RED, true);
  result.params = s.params;
  result.lookup =
      readTexture(s.frameLookup.id(), 0, settings.width, settings.height, 1, 4, GL_RGBA, true);
  result.receiverPlane =
      readTexture(s.frameReceiverPlane.id(), 0, settings.width, settings.height, 1, 2, GL_RG, true);
  result.uvDerivatives =
      readTexture(s.frameDerivatives.id(), 0, settings.width, settings.height, 1, 4, GL_RGBA, true);
  if (settings.technique == Technique::Esm &&
      s.params.esm.classifier != shaders::kEsmClassifyNone) {
    size_t drawn = 0, failed = 0;
    for (float v : result.diagnostic.data()) {
      drawn += v >= 0.0f;
      failed += v > 0.5f;
    }
    result.failureRatePercent = drawn == 0 ? 0.0 : 100.0 * double(failed) / double(drawn);
  }
  result.gpuTimes = {s.lightTimer.gpuMilliseconds(),     s.encodeTimer.gpuMilliseconds(),
                     s.prefilterTimer.gpuMilliseconds(), s.mipsTimer.gpuMilliseconds(),
                     s.auxiliaryTimer.gpuMilliseconds(), s.cameraTimer.gpuMilliseconds()};
  result.wallTimes = {s.lightTimer.wallMilliseconds(),     s.encodeTimer.wallMilliseconds(),
                      s.prefilterTimer.wallMilliseconds(), s.mipsTimer.wallMilliseconds(),
                      s.auxiliaryTimer.wallMilliseconds(), s.cameraTimer.wallMilliseconds()};
  result.memory = memoryReport(s);
  result.memory.geometry = gpuScene.bytes();
  return result;
}

namespace {

// Box-averages factor x factor blocks.
Image downsample(const Image& image, int factor) {
  if (factor == 1) return image;
  Image out(image.width() / factor, image.height() / factor, image.channels());
  const float weight = 1.0f / float(factor * factor);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      for (int c = 0; c < image.channels(); ++c) {
        float sum = 0.0f;
        for (int j = 0; j < factor; ++j) {
          for (int i = 0; i < factor; ++i) sum += image.at(x * factor + i, y * factor + j, c);
        }
        out.at(x, y, c) = sum * weight;
      }
    }
  }
  return out;
}

}  // namespace

// Pixels whose reference kernel needs more texel tests than one shader invocation may run are
// marked -1 by the camera pass (with the albedo in colour and the light amount in the
// diagnostic); the CPU twin evaluates them with the same shared code.
void Renderer::completeReferenceOnCpu(Image& visibility, Image& color, Image& diagnostic,
                                      const Image& lookup, const Image& receiverPlane,
                                      const Image& uvDerivatives) const {
  std::vector<std::pair<int, int>> pending;
  for (int y = 0; y < visibility.height(); ++y) {
    for (int x = 0; x < visibility.width(); ++x) {
      if (visibility.at(x, y) < 0.0f) pending.emplace_back(x, y);
    }
  }
  if (pending.empty()) return;
  const RenderSettings& settings = state_->settings;
  const CpuShadowLookup twin(readDepthMap(),
                             {Technique::Hard, settings.params, settings.filter, settings.blur,
                              settings.anisotropy, state_->halfRounding});
  for (const auto& [x, y] : pending) {
    LookupPixel pixel;
    pixel.uv = {lookup.at(x, y, 0), lookup.at(x, y, 1)};
    pixel.receiverDepth = lookup.at(x, y, 2);
    pixel.uvDx = {uvDerivatives.at(x, y, 0), uvDerivatives.at(x, y, 1)};
    pixel.uvDy = {uvDerivatives.at(x, y, 2), uvDerivatives.at(x, y, 3)};
    pixel.depthPerTexel = {receiverPlane.at(x, y, 0), receiverPlane.at(x, y, 1)};
    const float v = twin.referenceVisibility(pixel);
    const glm::vec3 albedo(color.at(x, y, 0), color.at(x, y, 1), color.at(x, y, 2));
    const glm::vec3 shaded =
        shaders::shadeLambert(albedo, settings.ambient, diagnostic.at(x, y), v);
    for (int c = 0; c < 3; ++c) color.at(x, y, c) = shaded[c];
    visibility.at(x, y) = v;
    diagnostic.at(x, y) = 0.0f;
  }
}

RenderResult Renderer::renderReference(const Scene& scene, const RenderSettings& settings,
                                       int supersample) {
  checkRange("reference supersampling", supersample, 1, 8);
  RenderSettings big = settings;
  big.msaaSamples = 1;
  big.width = settings.width * supersample;
  big.height = settings.height * supersample;
  validate(big);
  State& s = *state_;
  s.settings = big;
  s.params = big.params;
  s.uploadParameters();
  s.zmax = Texture();
  s.zmaxLevels = 0;
  s.satSums.reset();
  if (s.shadowMapSize != big.shadowMapSize || s.msaaSamples != 1 || s.lightFramebuffer == 0) {
    s.shadowMapSize = big.shadowMapSize;
    s.msaaSamples = 1;
    allocateLightPass(s);
  }
  allocateChannels(s, big);  // unused by the reference, but the camera program binds them
  allocateFrame(s, big.width, big.height);
  const GpuScene gpuScene(scene);
  const LightView light = fitLightView(scene);
  renderLightPass(s, gpuScene, light);
  renderCameraPass(s, scene, gpuScene, light, true);
  Image color = readTexture(s.frameColor.id(), 0, big.width, big.height, 1, 4, GL_RGBA, true);
  Image visibility =
      readTexture(s.frameVisibility.id(), 0, big.width, big.height, 1, 1, GL_RED, true);
  Image diagnostic =
      readTexture(s.frameDiagnostic.id(), 0, big.width, big.height, 1, 1, GL_RED, true);
  const Image lookup =
      readTexture(s.frameLookup.id(), 0, big.width, big.height, 1, 4, GL_RGBA, true);
  const Image receiverPlane =
      readTexture(s.frameReceiverPlane.id(), 0, big.width, big.height, 1, 2, GL_RG, true);
  const Image uvDerivatives =
      readTexture(s.frameDerivatives.id(), 0, big.width, big.height, 1, 4, GL_RGBA, true);
  completeReferenceOnCpu(visibility, color, diagnostic, lookup, receiverPlane, uvDerivatives);
  RenderResult result;
  result.color = downsample(color, supersample);
  result.visibility = downsample(visibility, supersample);
  result.diagnostic = downsample(diagnostic, supersample);
  if (supersample == 1) {
    result.lookup = lookup;
    result.receiverPlane = receiverPlane;
    result.uvDerivatives = uvDerivatives;
  }
  result.params = s.params;
  result.wallTimes.light = s.lightTimer.wallMilliseconds();
  result.wallTimes.camera = s.cameraTimer.wallMilliseconds();
  result.gpuTimes.light = s.lightTimer.gpuMilliseconds();
  result.gpuTimes.camera = s.cameraTimer.gpuMilliseconds();
  result.memory = memoryReport(s);
  result.memory.geometry = gpuScene.bytes();
  return result;
}

void Renderer::filterDepthMap(const Image& depth, const RenderSettings& settings) {
  RenderSettings single = settings;
  single.msaaSamples = 1;
  single.shadowMapSize = depth.width();
  if (depth.width() != depth.height() || depth.channels() != 1) {
    throw Error("filterDepthMap needs a square one-channel depth map");
  }
  validate(single);
  State& s = *state_;
  s.settings = single;
  s.params = single.params;
  s.shadowMapSize = depth.width();
  s.msaaSamples = 1;
  s.uploadParameters();
  s.uploadedDepth.emplace(GL_TEXTURE_2D);
  glTextureStorage2D(s.uploadedDepth->id(), 1, GL_R32F, depth.width(), depth.height());
  glTextureSubImage2D(s.uploadedDepth->id(), 0, 0, 0, depth.width(), depth.height(), GL_RED,
                      GL_FLOAT, depth.data().data());
  allocateChannels(s, single);
  encodeChannels(s, s.uploadedDepth->id(), false);
  prefilterChannels(s);
}

Image Renderer::readDepthMap() const {
  const State& s = *state_;
  if (s.msaaSamples > 1) throw Error("readDepthMap reads single-sampled light passes only");
  return readTexture(s.lightDepth.id(), 0, s.shadowMapSize, s.shadowMapSize, 1, 1, GL_RED, false);
}

int Renderer::channelMipLevels() const {
  return state_->channelLevels;
}

uint64_t Renderer::measuredChannelTextureBytes() const {
  const State& s = *state_;
  uint64_t bytes = 0;
  for (int level = 0; level < s.channelLevels; ++level) {
    GLint width = 0, height = 0, depth = 0, bits = 0;
    glGetTextureLevelParameteriv(s.channels.id(), level, GL_TEXTURE_WIDTH, &width);
    glGetTextureLevelParameteriv(s.channels.id(), level, GL_TEXTURE_HEIGHT, &height);
    glGetTextureLevelParameteriv(s.channels.id(), level, GL_TEXTURE_DEPTH, &depth);
    for (GLenum component : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE,
                             GL_TEXTURE_ALPHA_SIZE}) {
      GLint size = 0;
      glGetTextureLevelParameteriv(s.channels.id(), level, component, &size);
      bits += size;
    }
    bytes += uint64_t(width) * uint64_t(height) * uint64_t(depth) * uint64_t(bits / 8);
  }
  checkErrors("measuring the channel texture");
  return bytes;
}

Image Renderer::readChannels(int level) const {
  const State& s = *state_;
  checkRange("mip level", level, 0, s.channelLevels - 1);
  const int size = std::max(1, s.shadowMapSize >> level);
  const GLenum formats[5] = {0, GL_RED, GL_RG, GL_RGBA, GL_RGBA};
  Image all = readTexture(s.channels.id(), level, size, size, s.layout.layers,
                          s.layout.componentsPerTexel, formats[s.layout.componentsPerTexel], false);
  if (all.channels() == s.layout.channels) return all;
  Image trimmed(size, size, s.layout.channels);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      for (int c = 0; c < s.layout.channels; ++c) trimmed.at(x, y, c) = all.at(x, y, c);
    }
  }
  return trimmed;
}

Image Renderer::readZmaxLevel(int level) const {
  const State& s = *state_;
  if (s.zmax.id() == 0) throw Error("no Z-max pyramid: render ESM with classifier=zmax first");
  checkRange("Z-max level", level, 0, s.zmaxLevels - 1);
  const int size = std::max(1, s.shadowMapSize >> level);
  return readTexture(s.zmax.id(), level, size, size, 1, 1, GL_RED, false);
}

std::vector<SplitSample> Renderer::readSplitSamples() const {
  if (!state_->splitSamples)
    throw Error("no Lloyd samples: render LVSM with placement=lloyd first");
  return readSplitSamplesBuffer(*state_);
}

double Renderer::summedAreaBoxMean(int x0, int y0, int x1, int y1, int channel) const {
  const State& s = *state_;
  if (!s.satSums) throw Error("no summed-area table: render with the 'sat' filter first");
  const int size = s.shadowMapSize;
  struct Stats {
    double centre, step;
  };
  std::vector<Stats> stats(size_t(s.layout.channels));
  s.satStats->read(std::as_writable_bytes(std::span(stats)));
  auto prefix = [&](int x, int y) -> uint64_t {
    if (x < 0 || y < 0) return 0;
    uint64_t v = 0;
    const size_t index = (size_t(channel) * size_t(size) + size_t(y)) * size_t(size) + size_t(x);
    glGetNamedBufferSubData(s.satSums->id(), GLintptr(index * 8), 8, &v);
    return v;
  };
  const uint64_t wrapped =
      prefix(x1, y1) - prefix(x0 - 1, y1) - prefix(x1, y0 - 1) + prefix(x0 - 1, y0 - 1);
  const double area = double(x1 - x0 + 1) * double(y1 - y0 + 1);
  return shaders::summedAreaMean(double(int64_t(wrapped)), area, stats[size_t(channel)].step,
                                 stats[size_t(channel)].centre);
}

}  // namespace penumbra::gl
