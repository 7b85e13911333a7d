// Encode, separable blur, mip chain and summed-area table over every cascade's layers.
#include "shadow_map_filter.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdio>
#include <string>

#include "channel_dispatch.h"
#include "gl_formats.h"
#include "memory_plan.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/technique.h"

namespace penumbra::gl {

namespace {
constexpr unsigned kGroup = kChannelGroup;
// The fused prefilter's shared memory, the tile with its border and the rows' results (RGBA32F at
// most), must fit the 32 KiB every GL 4.5 device has for the largest radius it takes.
constexpr int fusedSharedBytes(int radius) {
  const int span = kFusedTile + 2 * radius;
  return 16 * (span * span + span * kFusedTile);
}
static_assert(fusedSharedBytes(kMaxFusedBlurRadius) <= 32768);
static_assert(fusedSharedBytes(kMaxFusedBlurRadius + 1) > 32768,
              "kMaxFusedBlurRadius is the largest");
}  // namespace

std::vector<ShaderDefine> formatDefines(const ChannelLayout& layout) {
  return {{"CHANNEL_FORMAT", imageFormatQualifier(layout)}};
}

std::vector<ShaderDefine> reductionDefines(Technique technique, const TechniqueParams& params,
                                           const ChannelLayout& layout) {
  // Unused components of the last layer reduce as means (lib/layer_reduction.glsl).
  std::vector<int> reductions(size_t(4 * layout.layers), int(ChannelReduction::Mean));
  for (int c = 0; c < layout.channels; ++c) {
    reductions[size_t(c)] = int(channelReduction(technique, params, c));
  }
  const bool allMean = std::all_of(reductions.begin(), reductions.end(),
                                   [](int r) { return r == int(ChannelReduction::Mean); });
  if (allMean) return {{"ALL_MEAN", "1"}};
  if (layout.layers != 1) return {};  // mixed reductions over several layers: resolved per texel
  std::string table = "ivec4(";
  for (size_t c = 0; c < 4; ++c) table += std::to_string(reductions[c]) + (c < 3 ? ", " : ")");
  return {{"LAYER_REDUCTIONS", table}};
}

std::vector<ShaderDefine> blurKernelDefines(const BlurSpec& spec) {
  // uintBitsToFloat of each weight's bits: a decimal literal would round through the compiler's
  // parser, and the CPU reference filters (src/core/filters.cpp) use these very floats.
  std::string weights = "float[](";
  const std::vector<float> w = blurWeights(spec);
  for (size_t i = 0; i < w.size(); ++i) {
    char bits[32];
    std::snprintf(bits, sizeof bits, "uintBitsToFloat(0x%08xu)", std::bit_cast<uint32_t>(w[i]));
    weights += bits;
    weights += i + 1 < w.size() ? ", " : ")";
  }
  return {blurRadiusDefine(spec), {"WEIGHTS", weights}};
}

std::vector<ShaderDefine> fusedTileDefines(const ChannelLayout& layout) {
  return {{"TILE", std::to_string(kFusedTile)},
          {"TEXEL_COMPONENTS", std::to_string(layout.componentsPerTexel)}};
}

int encodeRowsPerInvocation(const ChannelLayout& layout) {
  return layout.bytesPerTexel() * layout.layers <= 8 ? 4 : 2;
}

ShaderDefine encodeRowsDefine(const ChannelLayout& layout) {
  return {"ROWS_PER_INVOCATION", std::to_string(encodeRowsPerInvocation(layout))};
}

GroupGrid encodeGroups(const ChannelLayout& layout, int size) {
  const unsigned rows = unsigned(encodeRowsPerInvocation(layout));
  return {groups(size, kChannelGroup), groups(size, kChannelGroup * rows)};
}

ShaderDefine blurRadiusDefine(const BlurSpec& spec) {
  return {"RADIUS", std::to_string(spec.radius)};
}

ShaderDefine blurTapsAlikeDefine(const BlurSpec& spec, AlikeTaps alike) {
  return {"TAPS_ALIKE", sumsTapsAtUnitWeight(spec, alike) ? "1" : "0"};
}

void setBlurWeights(const Program& p, const BlurSpec& spec) {
  const std::vector<float> w = blurWeights(spec);
  glProgramUniform1fv(p.id(), glGetUniformLocation(p.id(), "weights"), GLsizei(w.size()), w.data());
}

void bindChannelImage(const Texture& texture, const ChannelLayout& layout, int level) {
  glBindImageTexture(0, texture.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, internalFormat(layout));
}

void bindChannelLayer(unsigned unit, const Texture& texture, const ChannelLayout& layout, int layer,
                      unsigned access) {
  glBindImageTexture(unit, texture.id(), 0, GL_FALSE, layer, access, internalFormat(layout));
}

void setSize(const Program& p, const char* name, int size) {
  glProgramUniform2i(p.id(), glGetUniformLocation(p.id(), name), size, size);
}

bool ChannelShape::operator==(const ChannelShape& o) const {
  return layout.channels == o.layout.channels && layout.layers == o.layout.layers &&
         layout.componentsPerTexel == o.layout.componentsPerTexel &&
         layout.format == o.layout.format && size == o.size && levels == o.levels &&
         cascades == o.cascades && scratch == o.scratch && summedArea == o.summedArea &&
         texture == o.texture;
}

ChannelShape channelShapeFor(const RenderSettings& settings, int cascades) {
  // PCF and the hard test read the light pass's depth: no channel texture, prefilter, mips or
  // scratch (memory_plan.h).
  ChannelShape shape;
  shape.layout = channelLayout(settings.technique, settings.params);
  shape.size = settings.shadowMapSize;
  shape.levels = channelLevelsFor(settings);
  shape.cascades = cascades;
  shape.scratch = blursIntoScratch(settings);
  shape.summedArea = buildsSummedAreaTable(settings);
  shape.texture = prefiltersChannels(settings.technique);
  return shape;
}

MipReducePrograms mipReducePrograms(ProgramCache& programs, std::vector<ShaderDefine> reductions,
                                    const ChannelLayout& layout) {
  reductions.push_back({"SOURCE_FORMAT", imageFormatQualifier(layout)});
  const Program& general =
      programs.graphics("passes/fullscreen.vert", "passes/mip_reduce.frag", reductions);
  reductions.push_back({"HALVING", "1"});
  return {programs.graphics("passes/fullscreen.vert", "passes/mip_reduce.frag", reductions),
          general, internalFormat(layout)};
}

void ShadowMapFilter::prepare(const ChannelShape& shape) {
  if (prepared_ && shape == shape_) return;
  shape_ = shape;
  prepared_ = true;
  const int layers = shape.layout.layers * shape.cascades;
  channels_ = Texture();
  if (shape.texture) {
    channels_ = Texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(channels_.id(), shape.levels, internalFormat(shape.layout), shape.size,
                       shape.size, layers);
  }
  scratch_ = Texture();
  if (shape.scratch) {
    scratch_ = Texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(scratch_.id(), 1, internalFormat(shape.layout), shape.size, shape.size,
                       layers);
  }
  satExtremes_.reset();
  satStats_.reset();
  satSums_.reset();
  if (shape.summedArea) {
    const SummedAreaSizes bytes =
        summedAreaSizes(shape.layout.channels * shape.cascades, shape.size);
    satExtremes_.emplace(bytes.extremes);
    satStats_.emplace(bytes.stats);
    satSums_.emplace(bytes.sums);
  }
  checkErrors("allocating the technique's channels");
}

void ShadowMapFilter::prefilter(ProgramCache& programs, const ParameterBlock& parameters,
                                unsigned depthTexture, int samples, Technique technique,
                                const TechniqueParams& params,
                                std::span<const BlurSpec> cascadeBlurs, bool fused) {
  if (!shape_.texture) {
    // PCF and the hard test: nothing is encoded or filtered, and no stage's time is measured.
    for (GpuTimer* t : {&encodeTimer, &prefilterTimer, &mipsTimer}) t->reset();
    return;
  }
  const bool prefilters = prefiltersChannels(technique);
  std::vector<ShaderDefine> defines = formatDefines(shape_.layout);
  for (ShaderDefine& d : reductionDefines(technique, params, shape_.layout)) {
    defines.push_back(std::move(d));
  }
  encodeTimer.begin();
  if (!fused) encode(programs, parameters, depthTexture, samples);
  encodeTimer.end();
  prefilterTimer.begin();
  const AlikeTaps alike = alikeTapsFor(technique, params);
  const bool blurs = prefilters && !shape_.summedArea &&
                     std::any_of(cascadeBlurs.begin(), cascadeBlurs.end(),
                                 [](const BlurSpec& b) { return b.radius > 0; });
  // The scratch texture is planned from the settings (blursIntoScratch), the fused path chosen
  // from this frame's kernels (fusesPrefilter): a blur that is not fused needs the scratch.
  assert(fused || !blurs || shape_.scratch);
  if (fused) {
    encodeAndBlurFused(programs, parameters, depthTexture, defines, cascadeBlurs, alike);
  } else if (blurs) {
    blurSeparately(programs, parameters, defines, cascadeBlurs, alike);
  }
  prefilterTimer.end();
  mipsTimer.begin();
  if (prefilters && shape_.levels > 1) {
    mipChain_.reduce(mipReducePrograms(programs, defines, shape_.layout), parameters, channels_,
                     shape_.levels, shape_.layout.layers * shape_.cascades, shape_.size);
  }
  if (prefilters && shape_.summedArea) buildSummedAreaTable(programs);
  mipsTimer.end();
  checkErrors("prefiltering the channels");
}

double ShadowMapFilter::timeEncode(ProgramCache& programs, const ParameterBlock& parameters,
                                   unsigned depthTexture, int samples, bool gpuTime) {
  if (!shape_.texture) throw Error("no encode to time: this technique reads the light's depth");
  repeatedEncodeTimer_.begin();
  encode(programs, parameters, depthTexture, samples);
  repeatedEncodeTimer_.end();
  return repeatedEncodeTimer_.milliseconds(gpuTime);
}

void ShadowMapFilter::encode(ProgramCache& programs, const ParameterBlock& parameters,
                             unsigned depthTexture, int samples) {
  std::vector<ShaderDefine> defines = formatDefines(shape_.layout);
  defines.push_back({"MSAA", samples > 1 ? "1" : "0"});
  defines.push_back({"LAYER_COUNT", std::to_string(shape_.layout.layers)});
  defines.push_back(encodeRowsDefine(shape_.layout));
  const Program& encode = programs.compute("passes/encode.comp", defines);
  parameters.bind();
  setSize(encode, "size", shape_.size);
  encode.set("sampleCount", samples);
  glBindTextureUnit(0, depthTexture);
  bindChannelImage(channels_, shape_.layout, 0);
  const GroupGrid grid = encodeGroups(shape_.layout, shape_.size);
  encode.dispatch(grid.x, grid.y, unsigned(shape_.cascades));
}

void ShadowMapFilter::blurSeparately(ProgramCache& programs, const ParameterBlock& parameters,
                                     const std::vector<ShaderDefine>& defines,
                                     std::span<const BlurSpec> cascadeBlurs, AlikeTaps alike) {
  const int layers = shape_.layout.layers;
  for (int cascade = 0; cascade < shape_.cascades; ++cascade) {
    const BlurSpec& spec = cascadeBlurs[size_t(cascade)];
    // One map: its radius and weights compiled in. Cascades' radii follow the view: uniforms
    // (blur.comp).
    const bool compiledKernel = shape_.cascades == 1;
    std::vector<ShaderDefine> kernelDefines = defines;
    kernelDefines.push_back(blurTapsAlikeDefine(spec, alike));
    if (compiledKernel) {
      for (ShaderDefine& d : blurKernelDefines(spec)) kernelDefines.push_back(std::move(d));
    }
    const Program& blur = programs.compute("passes/blur.comp", kernelDefines);
    if (!compiledKernel) {
      blur.set("radius", spec.radius);
      setBlurWeights(blur, spec);
    }
    parameters.bind();
    setSize(blur, "size", shape_.size);
    const GLint direction = glGetUniformLocation(blur.id(), "direction");
    for (int layer = 0; layer < layers; ++layer) {
      // Horizontal into scratch, vertical back, one layer at a time as 2D images.
      const int index = cascade * layers + layer;
      blur.set("layer", layer);
      bindChannelLayer(1, channels_, shape_.layout, index, GL_READ_ONLY);
      bindChannelLayer(0, scratch_, shape_.layout, index, GL_WRITE_ONLY);
      glProgramUniform2i(blur.id(), direction, 1, 0);
      blur.dispatch(groups(shape_.size, kGroup), groups(shape_.size, kGroup));
      bindChannelLayer(1, scratch_, shape_.layout, index, GL_READ_ONLY);
      bindChannelLayer(0, channels_, shape_.layout, index, GL_WRITE_ONLY);
      glProgramUniform2i(blur.id(), direction, 0, 1);
      blur.dispatch(groups(shape_.size, kGroup), groups(shape_.size, kGroup));
    }
  }
}

void ShadowMapFilter::encodeAndBlurFused(ProgramCache& programs, const ParameterBlock& parameters,
                                         unsigned depthTexture,
                                         const std::vector<ShaderDefine>& defines,
                                         std::span<const BlurSpec> cascadeBlurs, AlikeTaps alike) {
  glBindTextureUnit(0, depthTexture);
  bindChannelImage(channels_, shape_.layout, 0);
  for (int cascade = 0; cascade < shape_.cascades; ++cascade) {
    const BlurSpec& spec = cascadeBlurs[size_t(cascade)];
    // The radius compiled in; one map's weights too, cascades' as uniforms (their Gaussians'
    // sigmas follow the view: a variant per frame otherwise).
    const bool compiledWeights = shape_.cascades == 1;
    std::vector<ShaderDefine> fusedDefines = defines;
    if (compiledWeights) {
      for (ShaderDefine& d : blurKernelDefines(spec)) fusedDefines.push_back(std::move(d));
    } else {
      fusedDefines.push_back(blurRadiusDefine(spec));
    }
    fusedDefines.push_back(blurTapsAlikeDefine(spec, alike));
    for (ShaderDefine& d : fusedTileDefines(shape_.layout)) fusedDefines.push_back(std::move(d));
    const Program& fused = programs.compute("passes/prefilter_fused.comp", fusedDefines);
    if (!compiledWeights) setBlurWeights(fused, spec);
    parameters.bind();
    setSize(fused, "size", shape_.size);
    fused.set("cascade", cascade);
    fused.set("layerCount", shape_.layout.layers);
    fused.dispatch(groups(shape_.size, kFusedTile), groups(shape_.size, kFusedTile),
                   unsigned(shape_.layout.layers));
  }
}

void ShadowMapFilter::buildSummedAreaTable(ProgramCache& programs) {
  const int size = shape_.size;
  // Each cascade's channels are consecutive table channels (lib/summed_area.glsl).
  const int channels = shape_.layout.channels * shape_.cascades;
  // Both extremes of every channel are reduced with atomicMin: all ones is the empty reduction.
  const uint32_t allOnes = ~0u;
  glClearNamedBufferData(satExtremes_->id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &allOnes);
  satExtremes_->bindStorage(1);
  satStats_->bindStorage(2);
  satSums_->bindStorage(3);
  glBindTextureUnit(0, channels_.id());
  const Program& stats = programs.compute("passes/sat_stats.comp", {});
  setSize(stats, "size", size);
  stats.set("channelsPerCascade", shape_.layout.channels);
  stats.set("layersPerCascade", shape_.layout.layers);
  stats.dispatch(groups(size, 64), 1, unsigned(shape_.layout.layers * shape_.cascades));
  const Program& rows = programs.compute("passes/sat_rows.comp", {});
  setSize(rows, "size", size);
  rows.set("channelCount", channels);
  rows.set("channelsPerCascade", shape_.layout.channels);
  rows.set("layersPerCascade", shape_.layout.layers);
  rows.dispatch(groups(size, 64), unsigned(channels));
  const Program& columns = programs.compute("passes/sat_columns.comp", {});
  setSize(columns, "size", size);
  columns.set("channelCount", channels);
  columns.dispatch(groups(size, 64), unsigned(channels));
}

uint64_t ShadowMapFilter::channelBytes() const {
  if (!shape_.texture) return 0;
  return channelTextureBytes(shape_.layout, shape_.size, shape_.size, shape_.levels > 1) *
         uint64_t(shape_.cascades);
}

uint64_t ShadowMapFilter::scratchBytes() const {
  if (!shape_.scratch) return 0;
  return channelTextureBytes(shape_.layout, shape_.size, shape_.size, false) *
         uint64_t(shape_.cascades);
}

uint64_t ShadowMapFilter::summedAreaBytes() const {
  if (!satSums_) return 0;
  return satSums_->size() + satStats_->size() + satExtremes_->size();
}

}  // namespace penumbra::gl
