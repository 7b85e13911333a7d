// ShadowFilter's GL objects and what the last filter() made, for the renderer's passes and
// read-backs (the renderer is ShadowFilter's first host).
#pragma once

#include <epoxy/gl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "auxiliary_passes.h"
#include "gpu_timer.h"
#include "linear_depth_maps.h"
#include "penumbra/gl/program.h"
#include "penumbra/gl/shadow_filter.h"
#include "penumbra/shader_library.h"
#include "penumbra/shared/lookup_block.h"
#include "program_cache.h"
#include "shadow_map_filter.h"

namespace penumbra::gl {

struct ShadowFilter::State {
  ProgramCache programs;
  ParameterBlock parameters;
  ShadowMapFilter maps;
  ZmaxPyramid zmax;
  LloydPlacement lloyd;
  Buffer lookupBlock{sizeof(shaders::LookupBlock)};
  std::optional<shaders::LookupBlock> lookupUploaded;  // a warm frame uploads nothing unchanged
  // Per layer, the prefilter's cumulative weights (2 * kMaxBlurRadius + 1 each).
  Buffer blurCumulative{(2 * shaders::kMaxBlurRadius + 1) * shaders::kMaxCascades * sizeof(float)};
  std::vector<float> blurCumulativeUploaded;
  Texture importedDepth;  // the host's depth as linear R32F layers, when it needs converting
  int importedSize = 0, importedLayers = 0;
  unsigned rawSampler = 0;  // nearest, no depth comparison: reads a host's depth texels as stored
  LinearDepthMaps depth;    // the unfiltered depth of the last filter()
  bool filtered = false;    // false: nothing made yet, or prepareRawDepth (no channels)

  FilterSettings settings;  // of the last filter()
  DepthInput input;
  TechniqueParams params;  // in effect (EVSM's exponents clamped, LVSM's splits placed)
  // LVSM's Lloyd splits were placed on the GPU and `params` does not hold them yet: params()
  // reads them back on first use, so that a frame that reports nothing waits for nothing.
  bool splitsOnGpu = false;
  std::vector<BlurSpec> layerBlurs;
  bool fused = false;

  bool timing = false;
  GpuTimer importTimer, auxiliaryTimer;

  // This GL's limits, queried once.
  std::string device;
  GLint maxTextureSize = 0, maxSamples = 0, maxTextureUnits = 0, maxUniformBindings = 0,
        maxStorageBindings = 0;
  float maxAnisotropy = 1.0f;
  int64_t maxStorageBlock = 0;
  bool anisotropicFiltering = false, summedAreaTables = false;

  State();
  ~State();
  // Settings against their ranges and this GL's limits (the renderer's validate() too):
  // throws Error saying which and why.
  void checkFilter(const RenderSettings& renderSettings, int layers) const;
  // Bindings within this GL's limits, no two samplers or blocks on one binding.
  void checkBindings(const ShadowBindings& bindings) const;
};

// The defines a shader sampling the last filtered map needs besides the technique's
// (TECHNIQUE_ID, which ProgramCache adds): the summed-area table, the Z-max pyramid and
// multisampled depth (lib/lookup_access.glsl). `reference`: the filtered reference reads raw depth
// only.
std::vector<ShaderDefine> lookupVariantDefines(const ShadowFilter::State& s, bool reference);

// The size of the lookup's channel arrays for this technique and parameters
// (PENUMBRA_CHANNEL_CAPACITY, shared/technique_dispatch.h): its channels in whole texel layers.
ShaderDefine channelCapacityDefine(Technique technique, const TechniqueParams& params);

// What the renderer's own camera pass compiles in from the parameters, so the paths not taken
// fold away: ESM's classifier, fallback and filter space (lib/lookup_access.glsl lookupParams),
// the prefilter's kernel (lookupSettings),
// and the channel arrays' size (channelCapacityDefine). A host's preamble leaves them to the
// parameter block and kMaxChannels, so that a host shader compiled once follows parameter
// changes. On llvmpipe they took ESM's camera pass from 6x its minimal lookup to 3.5x, and
// LVSM's, the power CDF's and CSM's from 2.1-4.3x to 0.95-2.3x.
std::vector<ShaderDefine> lookupParameterDefines(const ShadowFilter::State& s);

}  // namespace penumbra::gl
