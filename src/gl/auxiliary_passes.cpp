// Technique-specific passes beside the shared pipeline: ESM's Z-max pyramid (ESM paper §3.3)
// and LVSM's Lloyd split placement (thesis §4.1.2).
#include <epoxy/gl.h>

#include "memory_plan.h"
#include "penumbra/gl/context.h"
#include "renderer_state.h"
#include "shared/constants.h"

namespace penumbra::gl {
namespace {

unsigned groups(int n) {
  return (unsigned(n) + 7u) / 8u;
}

}  // namespace

void buildZmaxPyramid(Renderer::State& s, unsigned depthTexture, bool multisampled) {
  s.zmaxLevels = mipLevelCount(s.shadowMapSize, s.shadowMapSize);
  s.zmax = Texture(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(s.zmax.id(), s.zmaxLevels, GL_R32F, s.shadowMapSize, s.shadowMapSize, 1);
  const Program& base = s.compute("passes/zmax_base.comp", {{"MSAA", multisampled ? "1" : "0"}});
  glProgramUniform2i(base.id(), glGetUniformLocation(base.id(), "size"), s.shadowMapSize,
                     s.shadowMapSize);
  base.set("sampleCount", s.msaaSamples);
  glBindTextureUnit(0, depthTexture);
  glBindImageTexture(0, s.zmax.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  base.dispatch(groups(s.shadowMapSize), groups(s.shadowMapSize));
  const Program& reduce = s.compute(
      "passes/mip_reduce.comp",
      {{"CHANNEL_FORMAT", "r32f"}, {"FORCE_REDUCTION", std::to_string(shaders::kReduceMax)}});
  const ChannelLayout depthOnly{1, 1, 1, StorageFormat::Float32};
  reduceMipLevels(s, reduce, s.zmax, depthOnly, s.zmaxLevels);
  checkErrors("building the Z-max pyramid");
}

std::vector<SplitSample> readSplitSamplesBuffer(const Renderer::State& s) {
  std::vector<SplitSample> samples(size_t(s.shadowMapSize - 1) * size_t(s.shadowMapSize - 1));
  s.splitSamples->read(std::as_writable_bytes(std::span(samples)));
  return samples;
}

void placeLayersByLloyd(Renderer::State& s, unsigned depthTexture, bool multisampled) {
  const int size = s.shadowMapSize;
  s.splitSamples.emplace(lloydSampleBytes(size));
  const Program& samples =
      s.compute("passes/split_samples.comp", {{"MSAA", multisampled ? "1" : "0"}});
  glProgramUniform2i(samples.id(), glGetUniformLocation(samples.id(), "size"), size, size);
  glBindTextureUnit(0, depthTexture);
  s.splitSamples->bindStorage(1);
  samples.dispatch(groups(size), groups(size));
  // Each step's sums are gathered on the GPU, row by row; the CPU adds the rows and moves the
  // splits, as the thesis reads back its reduction.
  const int rows = size - 1;
  Buffer rowSums(size_t(rows) * 4 * shaders::kMaxLayers * sizeof(float));
  const Program& gather = s.compute("passes/lloyd_sums.comp", {});
  gather.set("rowCount", rows);
  gather.set("rowLength", size - 1);
  s.splitSamples->bindStorage(1);
  rowSums.bindStorage(2);
  std::vector<float> partial(size_t(rows) * 4 * shaders::kMaxLayers);
  auto accumulate = [&](const shaders::LayerSplits& splits) {
    glProgramUniform4fv(gather.id(), glGetUniformLocation(gather.id(), "splitInterior"), 4,
                        &splits.interior[0][0]);
    gather.set("layerCount", splits.layerCount);
    gather.dispatch((unsigned(rows) + 63u) / 64u);
    rowSums.read(std::as_writable_bytes(std::span(partial)));
    LloydSums sums(splits.layerCount);
    for (int row = 0; row < rows; ++row) {
      const float* r = &partial[size_t(row) * 4 * shaders::kMaxLayers];
      for (int k = 0; k + 1 < splits.layerCount; ++k) {
        sums.clusterWeight[size_t(k)] += r[k];
        sums.clusterSum[size_t(k)] += r[shaders::kMaxLayers + k];
      }
      for (int l = 0; l < splits.layerCount; ++l) {
        sums.layerWeight[size_t(l)] += r[2 * shaders::kMaxLayers + l];
        sums.layerSum[size_t(l)] += r[3 * shaders::kMaxLayers + l];
      }
    }
    return sums;
  };
  shaders::LvsmParams& lvsm = s.params.lvsm;
  lvsm.splits = lloydRelaxation(lvsm.splits.layerCount, lvsm.lloydIterations,
                                std::max(2.0f * lvsm.overlap, 1e-3f), lvsm.overlap, accumulate);
  checkErrors("placing the layers");
}

}  // namespace penumbra::gl
