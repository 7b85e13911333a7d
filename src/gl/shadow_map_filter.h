// The technique-independent passes after the light pass, each the GPU twin of a CPU reference
// filter in src/core/: encode -> separable blur -> mip chain or summed-area table, for every
// cascade at once. Owns the channel texture, the blur's scratch texture and the summed-area
// buffers, and keeps them while their shape stays the same.
#pragma once

#include <optional>
#include <span>

#include "gpu_timer.h"
#include "penumbra/channel_layout.h"
#include "penumbra/filters.h"
#include "penumbra/gl/program.h"
#include "penumbra/gl/renderer.h"
#include "program_cache.h"

namespace penumbra::gl {

struct ChannelShape {
  ChannelLayout layout;
  int size = 0;      // texels per side
  int levels = 1;    // mip levels
  int cascades = 1;  // the texture holds layout.layers layers per cascade
  bool scratch = false;
  bool summedArea = false;
  bool operator==(const ChannelShape& o) const;
};

ChannelShape channelShapeFor(const RenderSettings& settings, int cascades);

// Bilinear within one named level, clamped to the edge.
Sampler levelBilinearSampler();

class ShadowMapFilter {
 public:
  void prepare(const ChannelShape& shape);
  // Depth (2D array, one layer per cascade, or its multisample twin) -> channels at level 0.
  void encode(ProgramCache& programs, const ParameterBlock& parameters, unsigned depthTexture,
              int samples);
  // Blurs each cascade with its own kernel, then builds mips or the summed-area table. PCF and
  // the hard test read raw depth: nothing to do for them.
  void prefilter(ProgramCache& programs, const ParameterBlock& parameters, Technique technique,
                 const TechniqueParams& params, std::span<const BlurSpec> cascadeBlurs);

  const ChannelShape& shape() const { return shape_; }
  const Texture& channels() const { return channels_; }
  bool hasSummedAreaTable() const { return satSums_.has_value(); }
  const Buffer& summedAreaStats() const { return *satStats_; }
  const Buffer& summedAreaSums() const { return *satSums_; }
  uint64_t channelBytes() const;
  uint64_t scratchBytes() const;
  uint64_t summedAreaBytes() const;

  GpuTimer encodeTimer, prefilterTimer, mipsTimer;

 private:
  void buildSummedAreaTable(ProgramCache& programs);

  ChannelShape shape_;
  bool prepared_ = false;
  Texture channels_;  // 2D array: layout.layers x cascades layers, `levels` levels
  Texture scratch_;   // 2D array, one level: the blur's intermediate
  Sampler levelBilinear_ = levelBilinearSampler();  // the mip pass's one-sample 2x2 means
  std::optional<Buffer> satRows_, satStats_, satSums_;
};

// Fills levels 1..levels-1 of a 2D-array texture (`layers` layers of `size`^2 at level 0) with
// `reduce` (passes/mip_reduce.comp in the layout's image format), `sampler` bound for its
// bilinear reads (0: the texture's own state, for texelFetch-only variants).
void reduceMipLevels(const Program& reduce, const ParameterBlock& parameters,
                     const Texture& texture, const ChannelLayout& layout, int layers, int size,
                     int levels, unsigned sampler = 0);

}  // namespace penumbra::gl
