// The technique-independent GPU passes after the light pass: encode, separable blur, mip chain
// and summed-area table, each the GPU twin of a CPU reference filter in src/core/.
#include <epoxy/gl.h>

#include "gl_formats.h"
#include "memory_plan.h"
#include "penumbra/filters.h"
#include "penumbra/gl/context.h"
#include "renderer_state.h"

namespace penumbra::gl {
namespace {

constexpr unsigned kGroup = 8;

unsigned groups(int n, unsigned size) {
  return (unsigned(n) + size - 1) / size;
}

std::vector<ShaderDefine> formatDefines(const ChannelLayout& layout) {
  return {{"CHANNEL_FORMAT", imageFormatQualifier(layout)}};
}

void bindChannelImage(const Texture& texture, const ChannelLayout& layout, int level) {
  glBindImageTexture(0, texture.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, internalFormat(layout));
}

void blurAxis(Renderer::State& s, const Program& blur, const Texture& from, const Texture& to,
              glm::ivec2 direction) {
  glBindTextureUnit(0, from.id());
  bindChannelImage(to, s.layout, 0);
  glProgramUniform2i(blur.id(), glGetUniformLocation(blur.id(), "direction"), direction.x,
                     direction.y);
  blur.dispatch(groups(s.shadowMapSize, kGroup), groups(s.shadowMapSize, kGroup));
}

}  // namespace

void reduceMipLevels(Renderer::State& s, const Program& reduce, const Texture& texture,
                     const ChannelLayout& layout, int levels) {
  s.bindParameters();
  reduce.set("layerCount", layout.layers);
  glBindTextureUnit(0, texture.id());
  for (int level = 0; level + 1 < levels; ++level) {
    const int source = std::max(1, s.shadowMapSize >> level);
    const int target = std::max(1, s.shadowMapSize >> (level + 1));
    reduce.set("sourceLevel", level);
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "sourceSize"), source,
                       source);
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "targetSize"), target,
                       target);
    bindChannelImage(texture, layout, level + 1);
    reduce.dispatch(groups(target, kGroup), groups(target, kGroup));
  }
}

namespace {

void buildMipChain(Renderer::State& s) {
  reduceMipLevels(s, s.compute("passes/mip_reduce.comp", formatDefines(s.layout)), s.channels,
                  s.layout, s.channelLevels);
}

void buildSummedAreaTable(Renderer::State& s) {
  const int size = s.shadowMapSize;
  const int channels = s.layout.channels;
  const SummedAreaSizes bytes = summedAreaSizes(channels, size);
  s.satRows.emplace(bytes.rows);
  s.satStats.emplace(bytes.stats);
  s.satSums.emplace(bytes.sums);
  s.satRows->bindStorage(1);
  s.satStats->bindStorage(2);
  s.satSums->bindStorage(3);
  glBindTextureUnit(0, s.channels.id());
  auto setCommon = [&](const Program& p) {
    glProgramUniform2i(p.id(), glGetUniformLocation(p.id(), "size"), size, size);
    p.set("channelCount", channels);
  };
  const Program& stats = s.compute("passes/sat_stats.comp", {});
  setCommon(stats);
  stats.dispatch(groups(size, 64), unsigned(channels));
  const Program& centre = s.compute("passes/sat_centre.comp", {});
  setCommon(centre);
  centre.dispatch(unsigned(channels));
  const Program& rows = s.compute("passes/sat_rows.comp", {});
  setCommon(rows);
  rows.dispatch(groups(size, 64), unsigned(channels));
  const Program& columns = s.compute("passes/sat_columns.comp", {});
  setCommon(columns);
  columns.dispatch(groups(size, 64), unsigned(channels));
}

}  // namespace

void allocateChannels(Renderer::State& s, const RenderSettings& settings) {
  // PCF and the hard test read raw depth: no prefilter, no mips, no scratch (memory_plan.h).
  s.layout = channelLayout(settings.technique, settings.params);
  s.channelLevels = channelLevelsFor(settings);
  s.channels = Texture(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(s.channels.id(), s.channelLevels, internalFormat(s.layout), s.shadowMapSize,
                     s.shadowMapSize, s.layout.layers);
  s.scratch = Texture();
  if (blursIntoScratch(settings)) {
    s.scratch = Texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(s.scratch.id(), 1, internalFormat(s.layout), s.shadowMapSize,
                       s.shadowMapSize, s.layout.layers);
  }
  s.satRows.reset();
  s.satStats.reset();
  s.satSums.reset();
  checkErrors("allocating the technique's channels");
}

void encodeChannels(Renderer::State& s, unsigned depthTexture, bool multisampled) {
  std::vector<ShaderDefine> defines = formatDefines(s.layout);
  defines.push_back({"MSAA", multisampled ? "1" : "0"});
  const Program& encode = s.compute("passes/encode.comp", defines);
  s.bindParameters();
  glProgramUniform2i(encode.id(), glGetUniformLocation(encode.id(), "size"), s.shadowMapSize,
                     s.shadowMapSize);
  encode.set("layerCount", s.layout.layers);
  encode.set("sampleCount", s.msaaSamples);
  glBindTextureUnit(0, depthTexture);
  bindChannelImage(s.channels, s.layout, 0);
  s.encodeTimer.begin();
  encode.dispatch(groups(s.shadowMapSize, kGroup), groups(s.shadowMapSize, kGroup));
  s.encodeTimer.end();
}

void prefilterChannels(Renderer::State& s) {
  const RenderSettings& settings = s.settings;
  const bool filtersAfterTest =
      settings.technique == Technique::Pcf || settings.technique == Technique::Hard;
  s.prefilterTimer.begin();
  if (!filtersAfterTest && s.scratch.id() != 0) {
    const Program& blur = s.compute("passes/blur.comp", formatDefines(s.layout));
    s.bindParameters();
    const std::vector<float> weights = blurWeights(settings.blur);
    glProgramUniform1fv(blur.id(), glGetUniformLocation(blur.id(), "weights"),
                        GLsizei(weights.size()), weights.data());
    blur.set("radius", settings.blur.radius);
    blur.set("layerCount", s.layout.layers);
    glProgramUniform2i(blur.id(), glGetUniformLocation(blur.id(), "size"), s.shadowMapSize,
                       s.shadowMapSize);
    blurAxis(s, blur, s.channels, s.scratch, {1, 0});
    blurAxis(s, blur, s.scratch, s.channels, {0, 1});
  }
  s.prefilterTimer.end();
  s.mipsTimer.begin();
  if (!filtersAfterTest && s.channelLevels > 1) buildMipChain(s);
  if (!filtersAfterTest && settings.filter == FilterMode::SummedArea) buildSummedAreaTable(s);
  s.mipsTimer.end();
  checkErrors("prefiltering the channels");
}

}  // namespace penumbra::gl
