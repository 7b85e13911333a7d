// ESM's Z-max pyramid and LVSM's Lloyd split placement on the GPU.
#include "auxiliary_passes.h"

#include <epoxy/gl.h>

#include <cassert>

#include "memory_plan.h"
#include "penumbra/gl/context.h"
#include "penumbra/shared/constants.h"
#include "shadow_map_filter.h"

namespace penumbra::gl {
namespace {

unsigned groups(int n) {
  return (unsigned(n) + 7u) / 8u;
}

}  // namespace

void ZmaxPyramid::build(ProgramCache& programs, const ParameterBlock& parameters,
                        const LinearDepthMaps& depth) {
  if (!built() || size_ != depth.size || layers_ != depth.layers) {
    size_ = depth.size;
    layers_ = depth.layers;
    levels_ = mipLevelCount(size_, size_);
    texture_ = Texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture_.id(), levels_, GL_R32F, size_, size_, layers_);
  }
  const Program& base =
      programs.compute("passes/zmax_base.comp", {{"MSAA", depth.multisampled() ? "1" : "0"}});
  glProgramUniform2i(base.id(), glGetUniformLocation(base.id(), "size"), size_, size_);
  base.set("sampleCount", depth.samples);
  glBindTextureUnit(0, depth.texture);
  glBindImageTexture(0, texture_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  base.dispatch(groups(size_), groups(size_), unsigned(layers_));
  const ChannelLayout depthOnly{1, 1, 1, StorageFormat::Float32};
  mipChain_.reduce(
      mipReducePrograms(programs, {{"FORCE_REDUCTION", std::to_string(shaders::kReduceMax)}},
                        depthOnly),
      parameters, texture_, levels_, layers_, size_);
  checkErrors("building the Z-max pyramid");
}

void ZmaxPyramid::release() {
  texture_ = Texture();
  levels_ = 0;
}

uint64_t ZmaxPyramid::bytes() const {
  if (!built()) return 0;
  const ChannelLayout r32f{1, 1, 1, StorageFormat::Float32};
  return channelTextureBytes(r32f, size_, size_, true) * uint64_t(layers_);
}

std::vector<SplitSample> LloydPlacement::readSamples() const {
  const size_t rowLength = size_t(size_ - 1);
  std::vector<int> counts(rowLength * size_t(layers_));
  rowCounts_->read(std::as_writable_bytes(std::span(counts)));
  std::vector<SplitSample> rows(rowLength * counts.size());
  samples_->read(std::as_writable_bytes(std::span(rows)));
  std::vector<SplitSample> weighted;
  for (size_t row = 0; row < counts.size(); ++row) {
    const auto first = rows.begin() + std::ptrdiff_t(row * rowLength);
    weighted.insert(weighted.end(), first, first + counts[row]);
  }
  return weighted;
}

shaders::LayerSplits LloydPlacement::readPlacedSplits() const {
  shaders::LayerSplits splits;
  state_->read(std::as_writable_bytes(std::span(&splits, 1)));
  return splits;
}

void LloydPlacement::release() {
  samples_.reset();
  rowCounts_.reset();
  groupSums_.reset();
  state_.reset();
}

void LloydPlacement::place(ProgramCache& programs, ParameterBlock& parameters,
                           const LinearDepthMaps& depth, const shaders::LvsmParams& lvsm) {
  const int size = depth.size;
  const int layers = depth.layers;
  if (!samples_ || size_ != size || layers_ != layers) {
    size_ = size;
    layers_ = layers;
    samples_.emplace(lloydSampleBytes(size) * size_t(layers));
    rowCounts_.emplace(lloydRowCountBytes(size, layers));
    groupSums_.emplace(lloydGroupSumBytes(size, layers));
    state_.emplace(sizeof(shaders::LloydState));
  }
  shaders::LloydState start{};
  start.splits = shaders::uniformLayerSplits(lvsm.splits.layerCount);
  glNamedBufferSubData(state_->id(), 0, sizeof start, &start);
  // Each row's weighted samples (every cascade's rows in turn); then each step's sums, row by
  // row and added up in groups of 64 rows, and the step itself, which adds the groups and moves
  // the splits. The thesis reads its reduction back each step; here the splits stay on the GPU
  // and go from the state straight into the parameter blocks.
  // The step that places the splits is the last one: at least one (validateParams).
  assert(lvsm.lloydIterations >= 1);
  const int rows = (size - 1) * layers;
  const unsigned rowGroups = lloydRowGroups(size, layers);
  const Program& samples =
      programs.compute("passes/split_samples.comp", {{"MSAA", depth.multisampled() ? "1" : "0"}});
  glProgramUniform2i(samples.id(), glGetUniformLocation(samples.id(), "size"), size, size);
  samples.set("rowCount", rows);
  glBindTextureUnit(0, depth.texture);
  samples_->bindStorage(1);
  rowCounts_->bindStorage(3);
  samples.dispatch(rowGroups);
  const Program& gather = programs.compute("passes/lloyd_sums.comp", {});
  gather.set("rowCount", rows);
  gather.set("rowLength", size - 1);
  const Program& step = programs.compute("passes/lloyd_step.comp", {});
  step.set("groupCount", int(rowGroups));
  step.set("lastStep", 0);
  step.set("overlap", lvsm.overlap);
  groupSums_->bindStorage(2);
  state_->bindStorage(4);
  for (int i = 0; i < lvsm.lloydIterations; ++i) {
    gather.dispatch(rowGroups);
    if (i + 1 == lvsm.lloydIterations) step.set("lastStep", 1);
    step.dispatch(1);
  }
  parameters.copyPlacedSplits(*state_);
  checkErrors("placing the layers");
}

}  // namespace penumbra::gl
