// ShadowFilter: a host's depth texture -> the technique's filtered shadow map, and the bindings
// and GLSL defines a host's shader needs to sample it.
#include "penumbra/gl/shadow_filter.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "gl_state.h"
#include "memory_plan.h"
#include "penumbra/channel_layout.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/render_setting_values.h"
#include "penumbra/params.h"
#include "penumbra/shared/technique_dispatch.h"
#include "renderer_state.h"
#include "shadow_filter_state.h"

namespace penumbra::gl {
namespace {

static_assert(sizeof(shaders::LookupBlock) == 48 + 16 * shaders::kMaxCascades,
              "LookupBlock mirrors its std140 layout");

std::string hex(int value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04x", unsigned(value));
  return text;
}

bool isDepthFormat(GLint format) {
  return format == GL_DEPTH_COMPONENT16 || format == GL_DEPTH_COMPONENT24 ||
         format == GL_DEPTH_COMPONENT32 || format == GL_DEPTH_COMPONENT32F ||
         format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8;
}

// The renderer's settings for a filter: the parts of RenderSettings the passes read.
RenderSettings renderSettingsFor(const FilterSettings& f, const DepthInput& depth) {
  RenderSettings r;
  r.technique = f.technique;
  r.params = f.params;
  r.shadowMapSize = depth.size;
  r.msaaSamples = depth.samples;
  r.blur = f.blur;
  r.filter = f.filter;
  r.fusePrefilter = f.fusePrefilter;
  r.anisotropy = f.anisotropy;
  // Per-layer kernels (cascades) keep the blur's intermediate even when every kernel fuses
  // today: their widths follow the view, and memory should not come and go between frames
  // (memory_plan.h blursIntoScratch, estimateMemory).
  r.cascades.count = f.layerBlurs.empty() ? 1 : int(f.layerBlurs.size());
  return r;
}

// What a host's texture is, from the GL itself: the input must be what it says.
void checkInputTexture(const DepthInput& d) {
  if (d.texture == 0 || !glIsTexture(d.texture)) {
    throw Error("ShadowFilter: depth texture " + std::to_string(d.texture) +
                " is not a GL texture name");
  }
  GLint target = 0;
  glGetTextureParameteriv(d.texture, GL_TEXTURE_TARGET, &target);
  const GLint expected = d.samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY
                         : d.layers == 1 && target == GL_TEXTURE_2D ? GL_TEXTURE_2D
                                                                    : GL_TEXTURE_2D_ARRAY;
  if (target != expected) {
    throw Error("ShadowFilter: depth texture " + std::to_string(d.texture) + " has target " +
                hex(target) + "; " + std::to_string(d.layers) + " layer(s) with " +
                std::to_string(d.samples) +
                " sample(s) need GL_TEXTURE_2D (one layer), GL_TEXTURE_2D_ARRAY or, multisampled, "
                "GL_TEXTURE_2D_MULTISAMPLE_ARRAY");
  }
  GLint width = 0, height = 0, layers = 1, format = 0;
  glGetTextureLevelParameteriv(d.texture, 0, GL_TEXTURE_WIDTH, &width);
  glGetTextureLevelParameteriv(d.texture, 0, GL_TEXTURE_HEIGHT, &height);
  if (target != GL_TEXTURE_2D)
    glGetTextureLevelParameteriv(d.texture, 0, GL_TEXTURE_DEPTH, &layers);
  glGetTextureLevelParameteriv(d.texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  if (width != d.size || height != d.size || layers < d.layers) {
    throw Error("ShadowFilter: depth texture " + std::to_string(d.texture) + " is " +
                std::to_string(width) + "x" + std::to_string(height) + " with " +
                std::to_string(layers) + " layer(s); the input says " + std::to_string(d.size) +
                "x" + std::to_string(d.size) + " with " + std::to_string(d.layers));
  }
  if (target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY) {
    GLint samples = 0;
    glGetTextureLevelParameteriv(d.texture, 0, GL_TEXTURE_SAMPLES, &samples);
    // A GL may give a multisampled texture more samples than asked (llvmpipe: 4 for 2), never
    // fewer; the filter reads the first d.samples of them.
    if (samples < d.samples) {
      throw Error("ShadowFilter: depth texture " + std::to_string(d.texture) + " has " +
                  std::to_string(samples) + " samples; the input says " +
                  std::to_string(d.samples));
    }
  }
  if (d.encoding == DepthEncoding::WindowDepth && !isDepthFormat(format)) {
    throw Error(
        "ShadowFilter: window depth needs a depth-format texture (GL_DEPTH_COMPONENT16, "
        "24, 32F or with stencil); texture " +
        std::to_string(d.texture) + " has internal format " + hex(format));
  }
  if (d.encoding == DepthEncoding::LinearDepth && format != GL_R32F) {
    throw Error("ShadowFilter: linear depth needs a GL_R32F texture; texture " +
                std::to_string(d.texture) + " has internal format " + hex(format));
  }
}

void checkInput(const DepthInput& d) {
  checkRange("ShadowFilter depth size", d.size, kMinShadowMapSize, kMaxTextureSizeAnyGl);
  checkRange("ShadowFilter depth layers", d.layers, 1, shaders::kMaxCascades);
  checkMsaaSamples(d.samples);
  if (d.samples > 1 && d.encoding != DepthEncoding::LinearDepth) {
    throw Error(
        "ShadowFilter: a multisampled input must be linear depth (R32F); resolve window "
        "depth to one sample first");
  }
  if (d.encoding == DepthEncoding::WindowDepth) {
    const bool ordered = d.nearDistance < d.farDistance;
    if (!ordered || (d.perspective && !(d.nearDistance > 0.0f)) || !std::isfinite(d.nearDistance) ||
        !std::isfinite(d.farDistance)) {
      throw Error("ShadowFilter: the light's near and far (" + std::to_string(d.nearDistance) +
                  ", " + std::to_string(d.farDistance) + ") must be finite with near < far" +
                  (d.perspective ? " and near > 0 for a perspective projection" : ""));
    }
  }
  checkInputTexture(d);
}

// What FilterSettings adds to the renderer's settings: the per-layer kernels.
void checkLayerKernels(const FilterSettings& f, const DepthInput& d) {
  if (!f.layerBlurs.empty() && int(f.layerBlurs.size()) != d.layers) {
    throw Error("ShadowFilter: " + std::to_string(f.layerBlurs.size()) + " layer blurs for " +
                std::to_string(d.layers) + " layers (give one per layer, or none)");
  }
  if (!f.layerKernelScales.empty() && int(f.layerKernelScales.size()) != d.layers) {
    throw Error("ShadowFilter: " + std::to_string(f.layerKernelScales.size()) +
                " layer kernel scales for " + std::to_string(d.layers) +
                " layers (give one per layer, or none)");
  }
  for (const BlurSpec& b : f.layerBlurs) {
    checkRange("layer blur radius", b.radius, 0, shaders::kMaxBlurRadius);
    checkedBlurSigma(b.sigma);
  }
  for (float scale : f.layerKernelScales) checkRange("layer kernel scale", scale, 1e-6f, 1e6f);
}

// GL 4.5 guarantees compute shaders; the fused prefilter's tile needs its 32 KiB of shared
// memory and the passes' 8x8 groups. Checked once, named in one line.
void checkCapabilities() {
  if (epoxy_gl_version() < 45) {
    throw Error("ShadowFilter needs OpenGL 4.5 core; the current context is " +
                std::to_string(epoxy_gl_version() / 10) + "." +
                std::to_string(epoxy_gl_version() % 10));
  }
  GLint shared = 0, invocations = 0;
  glGetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &shared);
  glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &invocations);
  if (shared < 32768 || invocations < 256) {
    throw Error(
        "ShadowFilter needs compute shaders with 32 KiB of shared memory and 256 "
        "invocations per group; this GL offers " +
        std::to_string(shared) + " bytes and " + std::to_string(invocations));
  }
}

}  // namespace

ShadowFilter::State::State() {
  device = std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ", " +
           reinterpret_cast<const char*>(glGetString(GL_VERSION));
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize);
  GLint colorSamples = 0, depthSamples = 0;
  glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &colorSamples);
  glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &depthSamples);
  maxSamples = std::min(colorSamples, depthSamples);
  // Anisotropic filtering is core from GL 4.6; on 4.5 it is ARB_ or EXT_texture_filter_anisotropic.
  anisotropicFiltering = epoxy_gl_version() >= 46 ||
                         epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
                         epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic");
  if (anisotropicFiltering) glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &maxAnisotropy);
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  maxStorageBlock = block;
  summedAreaTables = epoxy_has_gl_extension("GL_ARB_gpu_shader_int64") &&
                     epoxy_has_gl_extension("GL_ARB_gpu_shader_fp64");
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &maxTextureUnits);
  glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &maxUniformBindings);
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &maxStorageBindings);
  glCreateSamplers(1, &rawSampler);
  glSamplerParameteri(rawSampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(rawSampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(rawSampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  // The PCF fallback gathers 2x2 texels (lightDepthQuad): clamped as each texel fetch is.
  glSamplerParameteri(rawSampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(rawSampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void ShadowFilter::State::checkFilter(const RenderSettings& r, int layers) const {
  validateRenderSettings(r);  // the ranges on any GL; this GL's limits below
  checkRange("shadow-map size", r.shadowMapSize, kMinShadowMapSize, maxTextureSize);
  if (r.msaaSamples > maxSamples) {
    throw Error("MSAA samples " + std::to_string(r.msaaSamples) + ": this GL (" + device +
                ") supports at most " + std::to_string(maxSamples));
  }
  if (r.filter == FilterMode::AnisotropicDriver && !anisotropicFiltering) {
    throw Error(
        "the anisotropic-driver filter needs anisotropic texture filtering, which this GL (" +
        device + ") lacks: use --filter anisotropic (penumbra's own probes)");
  }
  checkRange("anisotropy", r.anisotropy, 1,
             std::min(kMaxAnisotropy, std::max(1, int(maxAnisotropy))));
  validateParams(r.technique, r.params);
  if (r.filter == FilterMode::SummedArea) {
    const TechniqueParams& p = r.params;
    checkSummedAreaFilterable(r.technique, p);
    if (prefiltersChannels(r.technique) && !summedAreaTables) {
      throw Error(
          "the summed-area filter needs GL_ARB_gpu_shader_int64 and "
          "GL_ARB_gpu_shader_fp64, which this GL (" +
          device + ") lacks: use --filter trilinear or anisotropic");
    }
    // The table is one storage buffer of 64-bit sums, indexed in 32 bits.
    const uint64_t entries =
        uint64_t(summedAreaSizes(channelCount(r.technique, p) * layers, r.shadowMapSize).sums) / 8;
    if (entries >= (uint64_t(1) << 32) || entries * 8 > uint64_t(maxStorageBlock)) {
      throw Error("the summed-area table of " + std::string(techniqueId(r.technique)) + " at " +
                  std::to_string(r.shadowMapSize) + "^2 (" + std::to_string(layers) +
                  " layer(s)) needs " + std::to_string(entries * 8) +
                  " bytes in one storage buffer; this GL holds " + std::to_string(maxStorageBlock) +
                  "; use a smaller shadow map");
    }
  }
}

void ShadowFilter::State::checkBindings(const ShadowBindings& b) const {
  auto inRange = [](const char* what, int value, int count) {
    if (value < 0 || value >= count) {
      throw Error(std::string("ShadowBindings::") + what + " " + std::to_string(value) +
                  " is out of range [0, " + std::to_string(count - 1) + "] on this GL");
    }
  };
  auto distinct = [](const char* what, std::initializer_list<int> values) {
    for (auto i = values.begin(); i != values.end(); ++i) {
      for (auto j = i + 1; j != values.end(); ++j) {
        if (*i == *j) {
          throw Error(std::string("ShadowBindings: two ") + what + " share binding " +
                      std::to_string(*i));
        }
      }
    }
  };
  inRange("channelUnit", b.channelUnit, maxTextureUnits);
  inRange("zmaxUnit", b.zmaxUnit, maxTextureUnits);
  inRange("depthUnit", b.depthUnit, maxTextureUnits);
  inRange("parameterBlock", b.parameterBlock, maxUniformBindings);
  inRange("layerRangeBlock", b.layerRangeBlock, maxUniformBindings);
  inRange("lookupBlock", b.lookupBlock, maxUniformBindings);
  inRange("satStatsBuffer", b.satStatsBuffer, maxStorageBindings);
  inRange("satSumsBuffer", b.satSumsBuffer, maxStorageBindings);
  inRange("blurWeightsBuffer", b.blurWeightsBuffer, maxStorageBindings);
  distinct("texture units", {b.channelUnit, b.zmaxUnit, b.depthUnit});
  distinct("uniform blocks", {b.parameterBlock, b.layerRangeBlock, b.lookupBlock});
  distinct("storage buffers", {b.satStatsBuffer, b.satSumsBuffer, b.blurWeightsBuffer});
}

ShadowFilter::State::~State() {
  glDeleteSamplers(1, &rawSampler);
}

std::vector<ShaderDefine> lookupVariantDefines(const ShadowFilter::State& s, bool reference) {
  const bool summedArea = !reference && s.filtered && s.settings.filter == FilterMode::SummedArea &&
                          s.maps.hasSummedAreaTable();
  const bool zmax = !reference && s.filtered && s.zmax.built();
  return {{"SUMMED_AREA", summedArea ? "1" : "0"},
          {"ZMAX", zmax ? "1" : "0"},
          {"MSAA", s.depth.multisampled() ? "1" : "0"},
          {"PENUMBRA_FILTER_MODE", std::to_string(int(s.settings.filter))}};
}

ShaderDefine channelCapacityDefine(Technique technique, const TechniqueParams& params) {
  const int channels = shaders::techniqueChannelCount(int(technique), params);
  return {"PENUMBRA_CHANNEL_CAPACITY", std::to_string(4 * ((channels + 3) / 4))};
}

std::vector<ShaderDefine> lookupParameterDefines(const ShadowFilter::State& s) {
  std::vector<ShaderDefine> defines{
      channelCapacityDefine(s.settings.technique, s.params),
      {"PENUMBRA_BLUR_KERNEL", std::to_string(blurKernelId(s.settings.blur.kernel))}};
  if (s.settings.technique == Technique::Esm) {
    const shaders::EsmParams& esm = s.params.esm;
    defines.push_back({"PENUMBRA_ESM_CLASSIFIER", std::to_string(esm.classifier)});
    defines.push_back({"PENUMBRA_ESM_FALLBACK", std::to_string(esm.fallback)});
    defines.push_back({"PENUMBRA_ESM_FILTER_SPACE", std::to_string(esm.filterSpace)});
  }
  return defines;
}

ShadowFilter::ShadowFilter() {
  checkCapabilities();
  state_ = std::make_unique<State>();
  setTiming(false);
}

ShadowFilter::~ShadowFilter() = default;

void ShadowFilter::setTiming(bool enabled) {
  State& s = *state_;
  s.timing = enabled;
  for (GpuTimer* t : {&s.importTimer, &s.auxiliaryTimer, &s.maps.encodeTimer,
                      &s.maps.prefilterTimer, &s.maps.mipsTimer}) {
    t->setEnabled(enabled);
  }
}

FilterTimes ShadowFilter::lastTimes() const {
  const State& s = *state_;
  FilterTimes t;
  t.import = s.importTimer.wallMilliseconds();
  t.auxiliary = s.auxiliaryTimer.wallMilliseconds();
  t.encode = s.maps.encodeTimer.wallMilliseconds();
  t.prefilter = s.maps.prefilterTimer.wallMilliseconds();
  t.mipsOrSat = s.maps.mipsTimer.wallMilliseconds();
  return t;
}

namespace {

// The host's depth as linear R32F layers: converted when it is window depth or a plain 2D
// texture, used as it is when it is penumbra's own layout already.
LinearDepthMaps importDepth(ShadowFilter::State& s, const DepthInput& d) {
  const bool direct =
      d.encoding == DepthEncoding::LinearDepth && (d.samples > 1 || d.layers > 1 || [&] {
        GLint target = 0;
        glGetTextureParameteriv(d.texture, GL_TEXTURE_TARGET, &target);
        return target == GL_TEXTURE_2D_ARRAY;
      }());
  s.importTimer.reset();
  if (direct) {
    s.importedDepth = Texture();
    s.importedSize = s.importedLayers = 0;
    return {d.texture, d.size, d.layers, d.samples};
  }
  if (s.importedDepth.id() == 0 || s.importedSize != d.size || s.importedLayers != d.layers) {
    s.importedDepth = Texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(s.importedDepth.id(), 1, GL_R32F, d.size, d.size, d.layers);
    s.importedSize = d.size;
    s.importedLayers = d.layers;
  }
  GLint target = 0;
  glGetTextureParameteriv(d.texture, GL_TEXTURE_TARGET, &target);
  const Program& program = s.programs.compute(
      "passes/depth_import.comp", {{"ARRAY_INPUT", target == GL_TEXTURE_2D_ARRAY ? "1" : "0"}});
  glProgramUniform2i(program.id(), glGetUniformLocation(program.id(), "size"), d.size, d.size);
  const bool perspective = d.encoding == DepthEncoding::WindowDepth && d.perspective;
  program.set("perspective", perspective ? 1 : 0);
  program.set("nearDistance", d.nearDistance);
  program.set("farDistance", d.farDistance);
  // A depth-stencil texture a host samples as stencil reads its stencil: depth for the import,
  // then the host's mode back (a texture's own state, which the state guard does not hold).
  GLint mode = GL_DEPTH_COMPONENT;
  glGetTextureParameteriv(d.texture, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
  if (mode != GL_DEPTH_COMPONENT) {
    glTextureParameteri(d.texture, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
  }
  s.importTimer.begin();
  glBindTextureUnit(0, d.texture);
  glBindSampler(0, s.rawSampler);  // a host's comparison mode must not turn texels into tests
  glBindImageTexture(0, s.importedDepth.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  program.dispatch((unsigned(d.size) + 7u) / 8u, (unsigned(d.size) + 7u) / 8u, unsigned(d.layers));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  s.importTimer.end();
  if (mode != GL_DEPTH_COMPONENT)
    glTextureParameteri(d.texture, GL_DEPTH_STENCIL_TEXTURE_MODE, mode);
  return {s.importedDepth.id(), d.size, d.layers, 1};
}

void uploadBlurWeights(ShadowFilter::State& s) {
  constexpr size_t kStride = 2 * shaders::kMaxBlurRadius + 1;
  std::vector<float> all(kStride * s.layerBlurs.size(), 0.0f);
  for (size_t c = 0; c < s.layerBlurs.size(); ++c) {
    const std::vector<float> cumulative = cumulativeBlurWeights(s.layerBlurs[c]);
    std::copy(cumulative.begin(), cumulative.end(), all.begin() + std::ptrdiff_t(c * kStride));
  }
  if (all == s.blurCumulativeUploaded) return;
  glNamedBufferSubData(s.blurCumulative.id(), 0, GLsizeiptr(all.size() * sizeof(float)),
                       all.data());
  s.blurCumulativeUploaded = std::move(all);
}

void uploadLookupBlock(ShadowFilter::State& s, bool reference) {
  const ChannelShape& shape = s.maps.shape();
  const FilterSettings& f = s.settings;
  shaders::LookupBlock b;
  std::memset(&b, 0, sizeof b);
  b.filterMode = int(f.filter);
  b.shadowMapSize = s.depth.size;
  // The reference follows the technique's lookup over every level the lookup may use.
  b.channelLevels =
      reference && usesMips(f.filter) ? mipLevelCount(s.depth.size, s.depth.size) : shape.levels;
  b.anisotropy = f.anisotropy;
  b.blurKernel = blurKernelId(f.blur.kernel);
  b.zmaxLevels = !reference && s.zmax.built() ? s.zmax.levels() : 0;
  b.layersPerCascade = shape.layout.layers;
  b.channelsPerCascade = shape.layout.channels;
  b.depthSamples = s.depth.samples;
  b.receiverPerspective =
      s.input.encoding == DepthEncoding::WindowDepth && s.input.perspective ? 1 : 0;
  b.receiverNear = s.input.nearDistance;
  b.receiverFar = s.input.farDistance;
  for (size_t i = 0; i < s.layerBlurs.size(); ++i) {
    const float scale = f.layerKernelScales.empty() ? 1.0f : f.layerKernelScales[i];
    b.layerKernel[i] = glm::vec4(float(s.layerBlurs[i].radius), s.layerBlurs[i].sigma, scale, 0.0f);
  }
  // Plain 4-byte fields and vec4s, zeroed first: bytewise equality is equality.
  if (s.lookupUploaded && std::memcmp(&*s.lookupUploaded, &b, sizeof b) == 0) return;
  glNamedBufferSubData(s.lookupBlock.id(), 0, sizeof b, &b);
  s.lookupUploaded = b;
}

// Everything about a request that can be refused, before any GL work.
void checkRequest(const ShadowFilter::State& s, const DepthInput& depth,
                  const FilterSettings& settings) {
  checkInput(depth);
  checkLayerKernels(settings, depth);
  s.checkFilter(renderSettingsFor(settings, depth), depth.layers);
}

// The settings and parameters of this filter, as the passes use them. Nothing is bound until
// the request completes: a pass that throws leaves no half-made map.
void adopt(ShadowFilter::State& s, const DepthInput& depth, const FilterSettings& settings) {
  s.filtered = false;
  s.splitsOnGpu = false;
  s.depth = LinearDepthMaps{};
  s.settings = settings;
  s.input = depth;
  s.params = settings.params;
  // EVSM's exponents as its storage holds them (the shaders clamp them the same way), so
  // params() reports what was used.
  s.params.evsm.positiveExponent =
      shaders::evsmClampExponent(s.params.evsm.positiveExponent, s.params.evsm.storage);
  s.params.evsm.negativeExponent =
      shaders::evsmClampExponent(s.params.evsm.negativeExponent, s.params.evsm.storage);
  if (settings.technique == Technique::Lvsm &&
      s.params.lvsm.placement == shaders::kLayerPlacementUniform) {
    s.params.lvsm.splits = shaders::uniformLayerSplits(s.params.lvsm.splits.layerCount);
  }
  s.layerBlurs = settings.layerBlurs.empty()
                     ? std::vector<BlurSpec>(size_t(depth.layers), settings.blur)
                     : settings.layerBlurs;
  s.programs.setTechnique(settings.technique);
}

}  // namespace

void ShadowFilter::filter(const DepthInput& depth, const FilterSettings& settings) {
  State& s = *state_;
  checkRequest(s, depth, settings);
  GlStateGuard guard;
  adopt(s, depth, settings);
  const RenderSettings r = renderSettingsFor(settings, depth);
  s.depth = importDepth(s, depth);
  s.auxiliaryTimer.reset();
  const bool lloyd = placesLayersByLloyd(r);
  s.parameters.upload(settings.technique, s.params);
  s.auxiliaryTimer.begin();
  if (buildsZmaxPyramid(r)) {
    s.zmax.build(s.programs, s.parameters, s.depth);
  } else {
    s.zmax.release();
  }
  if (lloyd) {
    s.lloyd.place(s.programs, s.parameters, s.depth, s.params.lvsm);
    s.splitsOnGpu = true;
  } else {
    s.lloyd.release();
  }
  s.auxiliaryTimer.end();
  if (!buildsZmaxPyramid(r) && !lloyd) s.auxiliaryTimer.reset();
  s.maps.prepare(channelShapeFor(r, depth.layers));
  s.fused = fusesPrefilter(r, s.layerBlurs);
  s.maps.prefilter(s.programs, s.parameters, s.depth.texture, s.depth.samples, settings.technique,
                   s.params, s.layerBlurs, s.fused);
  uploadBlurWeights(s);
  s.filtered = true;
  uploadLookupBlock(s, false);
  checkErrors("ShadowFilter::filter");
}

void ShadowFilter::prepareRawDepth(const DepthInput& depth, const FilterSettings& settings) {
  State& s = *state_;
  checkRequest(s, depth, settings);
  GlStateGuard guard;
  adopt(s, depth, settings);
  s.parameters.upload(settings.technique, s.params);
  s.depth = importDepth(s, depth);
  s.zmax.release();
  s.lloyd.release();
  s.auxiliaryTimer.reset();
  for (GpuTimer* t : {&s.maps.encodeTimer, &s.maps.prefilterTimer, &s.maps.mipsTimer}) t->reset();
  // The raw-depth lookup reads no channels, but takes the map's size and levels from the channel
  // shape (and binds its texture, if the technique has one): keep it this input's (a no-op when
  // equal).
  s.maps.prepare(channelShapeFor(renderSettingsFor(settings, depth), depth.layers));
  s.fused = false;
  uploadBlurWeights(s);
  s.filtered = false;
  uploadLookupBlock(s, true);
  checkErrors("ShadowFilter::prepareRawDepth");
}

namespace {

void setChannelSampling(const Texture& channels, int levels, const FilterSettings& settings,
                        bool anisotropicFiltering) {
  const FilterMode mode = settings.filter;
  const GLuint t = channels.id();
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, mode == FilterMode::Point ? GL_NEAREST : GL_LINEAR);
  GLint minFilter = GL_LINEAR;
  if (mode == FilterMode::Point) minFilter = GL_NEAREST;
  if (levels > 1) minFilter = GL_LINEAR_MIPMAP_LINEAR;
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, minFilter);
  // Only the driver's kernel needs the sampler's anisotropy: the modelled probes are textureLod.
  // (checkFilter refuses the driver's kernel where the GL has no anisotropic filtering).
  if (anisotropicFiltering) {
    const float anisotropy =
        mode == FilterMode::AnisotropicDriver ? float(settings.anisotropy) : 1.0f;
    glTextureParameterf(t, GL_TEXTURE_MAX_ANISOTROPY, anisotropy);
  }
}

}  // namespace

void ShadowFilter::bind(const ShadowBindings& b) const {
  const State& s = *state_;
  if (s.depth.texture == 0) throw Error("ShadowFilter::bind: nothing filtered yet");
  s.checkBindings(b);
  // PCF and the hard test have no channel texture (their lookup reads the depth): the unit is
  // left empty.
  if (s.maps.channels().id() != 0) {
    setChannelSampling(s.maps.channels(), s.maps.shape().levels, s.settings,
                       s.anisotropicFiltering);
  }
  glBindTextureUnit(unsigned(b.channelUnit), s.maps.channels().id());
  glBindSampler(unsigned(b.channelUnit), 0);
  if (s.filtered && s.zmax.built()) {
    glBindTextureUnit(unsigned(b.zmaxUnit), s.zmax.texture().id());
    glBindSampler(unsigned(b.zmaxUnit), 0);
  }
  glBindTextureUnit(unsigned(b.depthUnit), s.depth.texture);
  glBindSampler(unsigned(b.depthUnit), s.rawSampler);
  s.parameters.bind(b.parameterBlock, b.layerRangeBlock);
  s.lookupBlock.bindUniform(unsigned(b.lookupBlock));
  s.blurCumulative.bindStorage(unsigned(b.blurWeightsBuffer));
  if (s.filtered && s.settings.filter == FilterMode::SummedArea && s.maps.hasSummedAreaTable()) {
    s.maps.summedAreaStats().bindStorage(unsigned(b.satStatsBuffer));
    s.maps.summedAreaSums().bindStorage(unsigned(b.satSumsBuffer));
  }
}

std::string ShadowFilter::shaderPreamble(const ShadowBindings& b) const {
  if (state_->depth.texture == 0) {
    throw Error(
        "ShadowFilter::shaderPreamble: nothing filtered yet (the defines depend on the "
        "technique and the filter)");
  }
  state_->checkBindings(b);
  std::string text =
      "#define TECHNIQUE_ID " + std::to_string(int(state_->settings.technique)) + "\n";
  for (const ShaderDefine& d : lookupVariantDefines(*state_, false)) {
    text += "#define " + d.name + " " + d.value + "\n";
  }
  const std::pair<const char*, int> bindings[] = {
      {"PENUMBRA_CHANNEL_UNIT", b.channelUnit},
      {"PENUMBRA_ZMAX_UNIT", b.zmaxUnit},
      {"PENUMBRA_DEPTH_UNIT", b.depthUnit},
      {"PENUMBRA_PARAMETER_BLOCK", b.parameterBlock},
      {"PENUMBRA_LAYER_RANGE_BLOCK", b.layerRangeBlock},
      {"PENUMBRA_LOOKUP_BLOCK", b.lookupBlock},
      {"PENUMBRA_SAT_STATS_BUFFER", b.satStatsBuffer},
      {"PENUMBRA_SAT_SUMS_BUFFER", b.satSumsBuffer},
      {"PENUMBRA_BLUR_WEIGHTS_BUFFER", b.blurWeightsBuffer}};
  for (const auto& [name, value] : bindings) {
    text += std::string("#define ") + name + " " + std::to_string(value) + "\n";
  }
  return text;
}

unsigned ShadowFilter::channelTexture() const {
  return state_->maps.channels().id();
}

unsigned ShadowFilter::linearDepthTexture() const {
  return state_->depth.texture;
}

unsigned ShadowFilter::zmaxTexture() const {
  return state_->filtered && state_->zmax.built() ? state_->zmax.texture().id() : 0;
}

FilterMemory ShadowFilter::memory() const {
  const State& s = *state_;
  FilterMemory m;
  m.channels = s.maps.channelBytes();
  m.scratch = s.maps.scratchBytes();
  m.summedArea = s.maps.summedAreaBytes();
  m.auxiliary = s.zmax.bytes() + s.lloyd.bytes();
  m.importedDepth =
      uint64_t(s.importedSize) * uint64_t(s.importedSize) * uint64_t(s.importedLayers) * 4u;
  m.blocks = s.lookupBlock.size() + s.blurCumulative.size() + s.parameters.bytes();
  return m;
}

const TechniqueParams& ShadowFilter::params() const {
  State& s = *state_;
  if (s.splitsOnGpu) {
    s.params.lvsm.splits = s.lloyd.readPlacedSplits();
    s.splitsOnGpu = false;
  }
  return s.params;
}

int ShadowFilter::channelMipLevels() const {
  return state_->maps.shape().levels;
}

int ShadowFilter::layers() const {
  return state_->depth.layers;
}

}  // namespace penumbra::gl
