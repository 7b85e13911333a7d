// Technique-specific passes beside the shared pipeline: ESM's Z-max pyramid (ESM paper §3.3)
// and LVSM's Lloyd split placement (thesis §4.1.2). Each owns its GPU resources.
#pragma once

#include <optional>
#include <vector>

#include "linear_depth_maps.h"
#include "mip_chain_pass.h"
#include "penumbra/gl/program.h"
#include "penumbra/layer_placement.h"
#include "program_cache.h"

namespace penumbra::gl {

// The largest depth under each texel of each mip level, one layer per cascade.
class ZmaxPyramid {
 public:
  void build(ProgramCache& programs, const ParameterBlock& parameters,
             const LinearDepthMaps& depth);
  void release();
  bool built() const { return texture_.id() != 0; }
  const Texture& texture() const { return texture_; }
  int levels() const { return levels_; }
  uint64_t bytes() const;

 private:
  Texture texture_;  // 2D array, one R32F layer per cascade, full mip chain
  MipChainPass mipChain_;
  int levels_ = 0, size_ = 0, layers_ = 0;
};

// Places LVSM's layer splits by Lloyd relaxation over the second-occluder samples of every
// cascade's depth map (one depth metric for all cascades, so one placement serves them all),
// entirely on the GPU: the placed splits and the encode's ranges for them go into the parameter
// blocks without a wait; readPlacedSplits() reads them back for a report.
class LloydPlacement {
 public:
  void place(ProgramCache& programs, ParameterBlock& parameters, const LinearDepthMaps& depth,
             const shaders::LvsmParams& lvsm);
  void release();
  bool placed() const { return samples_.has_value(); }
  std::vector<SplitSample> readSamples() const;
  shaders::LayerSplits readPlacedSplits() const;  // waits for the placement
  uint64_t bytes() const {
    return samples_ ? samples_->size() + rowCounts_->size() + groupSums_->size() + state_->size()
                    : 0;
  }

 private:
  std::optional<Buffer> samples_;    // each row's weighted samples at the front of its slot
  std::optional<Buffer> rowCounts_;  // how many each row holds
  std::optional<Buffer> groupSums_;  // each step's sums, per group of 64 rows
  std::optional<Buffer> state_;      // shaders::LloydState: the splits between steps
  int size_ = 0, layers_ = 0;
};

}  // namespace penumbra::gl
