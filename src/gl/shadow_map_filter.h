// The technique-independent passes after the light pass, each the GPU twin of a CPU reference
// filter in src/core/: encode -> separable blur -> mip chain or summed-area table, for every
// cascade at once. Owns the channel texture, the blur's scratch texture and the summed-area
// buffers, and keeps them while their shape stays the same.
#pragma once

#include <optional>
#include <span>

#include "gpu_timer.h"
#include "mip_chain_pass.h"
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
  // False for PCF and the hard test: their lookup reads the light pass's depth, so there is no
  // channel texture and no encode (the encode's copy of the depth took 4.5 of the hard test's
  // 14 ms frame at compare's defaults on llvmpipe).
  bool texture = true;
  bool operator==(const ChannelShape& o) const;
};

ChannelShape channelShapeFor(const RenderSettings& settings, int cascades);

class ShadowMapFilter {
 public:
  void prepare(const ChannelShape& shape);
  // Depth (2D array, one layer per cascade, or its multisample twin) -> the technique's channels,
  // each cascade blurred with its own kernel, then mips or the summed-area table. `fused`: encode
  // and blur in one dispatch per cascade (passes/prefilter_fused.comp; fusesPrefilter decides),
  // else encode, then the two axes through the scratch texture. PCF and the hard test filter after
  // the test, over the light pass's depth: nothing runs for them (their timers read no work).
  void prefilter(ProgramCache& programs, const ParameterBlock& parameters, unsigned depthTexture,
                 int samples, Technique technique, const TechniqueParams& params,
                 std::span<const BlurSpec> cascadeBlurs, bool fused);

  const ChannelShape& shape() const { return shape_; }
  // The channel texture; id 0 where the shape has none (PCF, the hard test).
  const Texture& channels() const { return channels_; }
  bool hasSummedAreaTable() const { return satSums_.has_value(); }
  const Buffer& summedAreaStats() const { return *satStats_; }
  const Buffer& summedAreaSums() const { return *satSums_; }
  uint64_t channelBytes() const;
  uint64_t scratchBytes() const;
  uint64_t summedAreaBytes() const;

  GpuTimer encodeTimer, prefilterTimer, mipsTimer;
  // bench --passes: the last prefilter's encode dispatched again on its own (level 0 then holds
  // the unfiltered channels until the next prefilter), timed by a timer of its own (encodeTimer
  // keeps the prefilter's); its milliseconds, the GPU query's (gpuTime) or the wall clock's.
  double timeEncode(ProgramCache& programs, const ParameterBlock& parameters, unsigned depthTexture,
                    int samples, bool gpuTime);

 private:
  void encode(ProgramCache& programs, const ParameterBlock& parameters, unsigned depthTexture,
              int samples);
  void blurSeparately(ProgramCache& programs, const ParameterBlock& parameters,
                      const std::vector<ShaderDefine>& defines,
                      std::span<const BlurSpec> cascadeBlurs, AlikeTaps alike);
  void encodeAndBlurFused(ProgramCache& programs, const ParameterBlock& parameters,
                          unsigned depthTexture, const std::vector<ShaderDefine>& defines,
                          std::span<const BlurSpec> cascadeBlurs, AlikeTaps alike);
  void buildSummedAreaTable(ProgramCache& programs);

  GpuTimer repeatedEncodeTimer_;  // timeEncode's
  ChannelShape shape_;
  bool prepared_ = false;
  Texture channels_;  // 2D array: layout.layers x cascades layers, `levels` levels
  Texture scratch_;   // 2D array, one level: the blur's intermediate
  MipChainPass mipChain_;
  std::optional<Buffer> satExtremes_, satStats_, satSums_;
};

// The mip pass's programs for a layout's reductions (passes/mip_reduce.frag), reading the level
// above as an image of the layout's format.
MipReducePrograms mipReducePrograms(ProgramCache& programs, std::vector<ShaderDefine> reductions,
                                    const ChannelLayout& layout);

}  // namespace penumbra::gl
