// The CPU twin of the camera pass's lookup: the CPU reference filters build the textures, and
// the shared lookup reads them through the access functions of shared/lookup_access.h.
#include "penumbra/shadow_lookup.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/channel_layout.h"
#include "penumbra/error.h"
#include "penumbra/params.h"
#include "penumbra/shared/filtered_reference.h"
#include "penumbra/shared/shadow_lookup.h"
#include "penumbra/storage_format.h"
#include "penumbra/summed_area_table.h"

namespace penumbra {

namespace shaders {

struct CpuLookupTextures {
  LookupSettings settings{};
  Image depth;
  std::vector<Image> channels;  // mip chain; level 0 alone without mips
  std::optional<SummedAreaTable> summedArea;
  std::vector<Image> zmax;
  std::vector<float> blurCumulative;
};

vec4 channelTexel(LookupSources s, int layer, ivec2 texel, int level) {
  const Image& image = s.textures->channels.at(size_t(level));  // none for PCF and the hard test
  vec4 v(0.0f);
  for (int k = 0; k < 4; ++k) {
    const int c = 4 * layer + k;
    if (c < image.channels()) v[k] = image.at(texel.x, texel.y, c);
  }
  return v;
}

vec4 channelLinear(LookupSources s, int layer, vec2 uv, float lod) {
  const CpuLookupTextures& t = *s.textures;
  const TrilinearLevels levels = trilinearLevels(lod, int(t.channels.size()));
  const int size = t.settings.shadowMapSize;
  LayerAccumulator a = startLayerReduction(ivec4(kReduceMean), 0.0f);
  a = accumulateBilinear(s, a, layer, uv, levels.level, mipLevelSize(size, levels.level),
                         1.0f - levels.fraction);
  a = accumulateBilinear(s, a, layer, uv, levels.next, mipLevelSize(size, levels.next),
                         levels.fraction);
  return layerReductionResult(a);
}

// The driver's anisotropic filter, which the CPU cannot know: the usual model of it, the probes
// the filtered reference models (anisotropic-driver's CPU twin is approximate).
vec4 channelAnisotropic(LookupSources s, int layer, vec2 uv, vec2 uvDx, vec2 uvDy) {
  return channelProbes(s, s.textures->settings, layer, uv, uvDx, uvDy);
}

float lightDepthTexel(LookupSources s, ivec2 texel) {
  return s.textures->depth.at(texel.x, texel.y);
}

vec4 lightDepthQuad(LookupSources s, ivec2 texel, int size) {
  return lightDepthQuadOfTexels(s, texel, size);
}

float zmaxTexel(LookupSources s, ivec2 texel, int level) {
  return s.textures->zmax[size_t(level)].at(texel.x, texel.y);
}

float blurCumulativeWeight(LookupSources s, int u) {
  return s.textures->blurCumulative[size_t(u + s.textures->settings.blurRadius)];
}

uint64_t summedAreaPrefix(LookupSources s, int channel, int x, int y) {
  return s.textures->summedArea->prefixSum(x, y, channel);
}

double summedAreaCentre(LookupSources s, int channel) {
  return s.textures->summedArea->centre(channel);
}

double summedAreaStep(LookupSources s, int channel) {
  return s.textures->summedArea->step(channel);
}

}  // namespace shaders

namespace {

Image quantized(Image image, StorageFormat storage, HalfRounding rounding) {
  for (float& v : image.data()) v = quantizeToStorage(v, storage, rounding);
  return image;
}

bool isPowerOfTwo(int n) {
  return n > 0 && (n & (n - 1)) == 0;
}

// The channels the renderer's encode and prefilter make (shadow_map_filter.cpp), every stage
// rounded to the storage format as the GPU's textures round it: level 0, then its mip chain where
// the filter mode reads one.
std::vector<Image> prefilteredChannels(const Image& depth, const LookupConfig& config) {
  const Technique technique = config.technique;
  const TechniqueParams& params = config.params;
  const int size = depth.width();
  const int count = channelCount(technique, params);
  const StorageFormat storage = techniqueStorage(technique, params);
  const HalfRounding rounding = config.halfRounding;
  Image channels(size, size, count);
  std::vector<float> encoded(static_cast<size_t>(count));
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      encodeDepth(technique, params, depth.at(x, y), encoded);
      for (int c = 0; c < count; ++c)
        channels.at(x, y, c) = quantizeToStorage(encoded[size_t(c)], storage, rounding);
    }
  }
  std::vector<ChannelReduction> reductions;
  for (int c = 0; c < count; ++c) reductions.push_back(channelReduction(technique, params, c));
  const float logExponent = params.esm.exponent;
  if (config.blur.radius > 0 && config.filter != FilterMode::SummedArea) {
    const AlikeTaps alike = alikeTapsFor(technique, params);
    for (const bool horizontal : {true, false}) {
      channels = quantized(
          separableFilterPass(channels, config.blur, horizontal, reductions, logExponent, alike),
          storage, rounding);
    }
  }
  std::vector<Image> levels{std::move(channels)};
  if (usesMips(config.filter)) {
    while (levels.back().width() > 1) {
      levels.push_back(
          quantized(reduceMipLevel(levels.back(), reductions, logExponent), storage, rounding));
    }
  }
  return levels;
}

// The settings the reference reads: every mip level for the mip-mapped filter modes.
shaders::LookupSettings referenceSettings(shaders::LookupSettings settings, FilterMode filter) {
  const int size = settings.shadowMapSize;
  if (usesMips(filter)) {
    if (!isPowerOfTwo(size)) {
      throw Error(
          "the filtered reference of mip-mapped lookups needs a power-of-two shadow-map "
          "size; " +
          std::to_string(size) + " is not");
    }
    settings.channelLevels = mipLevelCount(size, size);
  }
  return settings;
}

}  // namespace

CpuShadowLookup::CpuShadowLookup(const Image& depth, const LookupConfig& config)
    : textures_(std::make_unique<shaders::CpuLookupTextures>()), config_(config) {
  if (depth.width() != depth.height() || depth.channels() != 1 || depth.width() < 1) {
    throw Error("the CPU shadow lookup needs a square one-channel depth map");
  }
  validateParams(config.technique, config.params);
  if (config.anisotropy < 1 || config.anisotropy > 16) {
    throw Error("anisotropy " + std::to_string(config.anisotropy) + " is out of range [1, 16]");
  }
  if (config.filter == FilterMode::SummedArea) {
    checkSummedAreaFilterable(config.technique, config.params);
  }
  shaders::CpuLookupTextures& t = *textures_;
  const Technique technique = config.technique;
  const TechniqueParams& params = config.params;
  const int size = depth.width();
  t.depth = depth;
  t.blurCumulative = cumulativeBlurWeights(config.blur);

  // PCF and the hard test read the depth itself (lightDepthTexel): like the renderer, the twin
  // encodes and prefilters nothing for them.
  if (prefiltersChannels(technique)) {
    t.channels = prefilteredChannels(depth, config);
    if (config.filter == FilterMode::SummedArea) t.summedArea.emplace(t.channels.front());
  }
  if (technique == Technique::Esm && params.esm.classifier == shaders::kEsmClassifyZmax) {
    const std::vector<ChannelReduction> max{ChannelReduction::Max};
    t.zmax = buildMipChain(depth, max);
  }

  t.settings.filterMode = int(config.filter);
  t.settings.shadowMapSize = size;
  t.settings.channelLevels = std::max(1, int(t.channels.size()));  // as the renderer's: 1 unmipped
  t.settings.anisotropy = config.anisotropy;
  t.settings.blurKernel = blurKernelId(config.blur.kernel);
  t.settings.blurRadius = config.blur.radius;
  t.settings.blurSigma = config.blur.sigma;
  t.settings.zmaxLevels = int(t.zmax.size());
  t.settings.kernelScale = config.kernelScale;
}

CpuShadowLookup::~CpuShadowLookup() = default;

LookupSample CpuShadowLookup::lookup(const LookupPixel& p) const {
  const shaders::LookupSources sources{textures_.get()};
  const shaders::ShadowSample s = shaders::shadowLookup(
      sources, textures_->settings, int(config_.technique), config_.params, p.uv, p.receiverDepth,
      p.uvDx, p.uvDy, p.depthPerTexel, config_.softLight);
  return {s.visibility, s.diagnostic};
}

std::vector<float> CpuShadowLookup::filteredChannels(const LookupPixel& p) const {
  if (!prefiltersChannels(config_.technique)) return {};
  const shaders::LookupSources sources{textures_.get()};
  const shaders::FilteredChannels f =
      shaders::filterChannels(sources, textures_->settings, int(config_.technique), config_.params,
                              p.uv, p.uvDx, p.uvDy, std::clamp(p.receiverDepth, 0.0f, 1.0f));
  const int count = channelCount(config_.technique, config_.params);
  return std::vector<float>(f.values, f.values + count);
}

bool CpuShadowLookup::referenceLeftToCpu(const LookupPixel& p) const {
  return shaders::referenceLeftToCpu(referenceSettings(textures_->settings, config_.filter), p.uv,
                                     p.uvDx, p.uvDy);
}

float CpuShadowLookup::referenceVisibility(const LookupPixel& p) const {
  const shaders::LookupSettings settings = referenceSettings(textures_->settings, config_.filter);
  const shaders::LookupSources sources{textures_.get()};
  return std::clamp(shaders::referenceVisibility(sources, settings, p.uv, p.receiverDepth, p.uvDx,
                                                 p.uvDy, p.depthPerTexel),
                    0.0f, 1.0f);
}

}  // namespace penumbra
