// The allocations of a render, from its settings, and the largest scene buffers a GL draws from.
#include "memory_plan.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "gl_formats.h"
#include "penumbra/channel_layout.h"
#include "penumbra/gl/scene_buffers.h"
#include "penumbra/point_light.h"
#include "penumbra/scene.h"
#include "penumbra/shared/constants.h"
#include "penumbra/shared/layer_placement.h"
#include "penumbra/shared/summed_area.h"

namespace penumbra::gl {
namespace {

// The camera pass's render targets (camera_pass.cpp, CameraPass::prepare).
enum class FrameTargetUse { Always, Diagnostics, LookupInputs };
struct FrameTarget {
  std::string_view what;
  GLenum format;
  int bytesPerPixel;
  FrameTargetUse use;  // allocated always, or only when the frame writes them
};
constexpr FrameTarget kFrameTargets[] = {
    {"frame lookup target", GL_RGBA32F, 16, FrameTargetUse::LookupInputs},
    {"frame receiver-plane target", GL_RG32F, 8, FrameTargetUse::LookupInputs},
    {"frame colour target", GL_RGBA16F, 8, FrameTargetUse::Always},
    {"frame visibility target", GL_R32F, 4, FrameTargetUse::Diagnostics},
    {"frame diagnostic target", GL_R32F, 4, FrameTargetUse::Diagnostics},
    {"frame depth buffer", GL_DEPTH_COMPONENT32F, 4, FrameTargetUse::Always},
    {"frame uv-derivatives target", GL_RGBA32F, 16, FrameTargetUse::LookupInputs},
    {"frame cascade target", GL_RG32F, 8, FrameTargetUse::LookupInputs},
};

// `diagnostics` as writesDiagnostics gives it: true wherever lookupInputs is.
bool allocates(const FrameTarget& target, bool diagnostics, bool lookupInputs) {
  switch (target.use) {
    case FrameTargetUse::Always: return true;
    case FrameTargetUse::Diagnostics: return diagnostics;
    case FrameTargetUse::LookupInputs: return lookupInputs;
  }
  return true;
}

}  // namespace

int channelLevelsFor(const RenderSettings& s) {
  return prefiltersChannels(s.technique) && usesMips(s.filter)
             ? mipLevelCount(s.shadowMapSize, s.shadowMapSize)
             : 1;
}

bool blursIntoScratch(const RenderSettings& s) {
  // One map whose kernel runs fused needs no intermediate; cascades keep it, since a cascade's
  // kernel (scaled to the same world width) may outgrow the fused tile.
  return prefiltersChannels(s.technique) && s.blur.radius > 0 &&
         s.filter != FilterMode::SummedArea &&
         !(s.cascades.count == 1 && fusesPrefilter(s, s.blur.radius));
}

bool fusesPrefilter(const RenderSettings& s, int radius) {
  return s.fusePrefilter && prefiltersChannels(s.technique) && s.filter != FilterMode::SummedArea &&
         radius > 0 && radius <= kMaxFusedBlurRadius && s.msaaSamples == 1 &&
         techniqueStorage(s.technique, s.params) == StorageFormat::Float32;
}

bool fusesPrefilter(const RenderSettings& s, std::span<const BlurSpec> cascadeBlurs) {
  // A cascade whose kernel scaled below a texel (radius 0) rides along: its dispatch encodes
  // and passes each texel through, as the separate passes' one-tap blur does.
  const bool blurs = std::any_of(cascadeBlurs.begin(), cascadeBlurs.end(),
                                 [](const BlurSpec& b) { return b.radius > 0; });
  return blurs && std::all_of(cascadeBlurs.begin(), cascadeBlurs.end(), [&](const BlurSpec& b) {
           return fusesPrefilter(s, std::max(b.radius, 1));
         });
}

bool buildsSummedAreaTable(const RenderSettings& s) {
  return prefiltersChannels(s.technique) && s.filter == FilterMode::SummedArea;
}

bool buildsZmaxPyramid(const RenderSettings& s) {
  return s.technique == Technique::Esm && s.params.esm.classifier == shaders::kEsmClassifyZmax;
}

bool placesLayersByLloyd(const RenderSettings& s) {
  return s.technique == Technique::Lvsm && s.params.lvsm.placement == shaders::kLayerPlacementLloyd;
}

uint64_t lightPassBytes(int shadowMapSize, int samples) {
  // R32F linear depth and a D32F depth buffer, per sample.
  return uint64_t(shadowMapSize) * uint64_t(shadowMapSize) * (4 + 4) * uint64_t(samples);
}

bool fitsDepthBounds(const RenderSettings& s) {
  return s.cascades.count > 1 && s.cascades.fitDepthBounds;
}

uint64_t depthBoundsBytes(int width, int height) {
  return uint64_t(width) * uint64_t(height) * 4 +
         kDepthBoundsMeasurementsInFlight * kDepthBoundsBytesPerMeasurement;
}

bool writesDiagnostics(const RenderSettings& s) {
  return s.lookupInputs ||
         (s.readBack & (frame_image::kVisibility | frame_image::kDiagnostic)) != 0;
}

uint64_t frameBytes(int width, int height, bool diagnostics, bool lookupInputs) {
  uint64_t perPixel = 0;
  for (const FrameTarget& target : kFrameTargets) {
    if (allocates(target, diagnostics, lookupInputs)) perPixel += target.bytesPerPixel;
  }
  return uint64_t(width) * uint64_t(height) * perPixel;
}

SummedAreaSizes summedAreaSizes(int channels, int shadowMapSize) {
  const size_t c = size_t(channels), n = size_t(shadowMapSize);
  return {c * 2 * sizeof(uint32_t), c * 16,
          c * n * size_t(shaders::summedAreaRowPitch(shadowMapSize)) * 8};
}

unsigned lloydRowGroups(int shadowMapSize, int cascades) {
  const unsigned rows = unsigned(shadowMapSize - 1) * unsigned(cascades);
  return (rows + unsigned(shaders::kLloydRowsPerGroup) - 1u) /
         unsigned(shaders::kLloydRowsPerGroup);
}

size_t lloydGroupSumBytes(int shadowMapSize, int cascades) {
  // Per group of sample rows: cluster and layer weights and sums.
  return size_t(lloydRowGroups(shadowMapSize, cascades)) * shaders::kLloydQuantities *
         sizeof(float);
}

size_t lloydRowCountBytes(int shadowMapSize, int cascades) {
  return size_t(shadowMapSize - 1) * size_t(cascades) * sizeof(int32_t);
}

size_t lloydSampleBytes(int shadowMapSize) {
  const size_t inner = size_t(shadowMapSize - 1);
  return inner * inner * sizeof(SplitSample);
}

int shadowMapLayers(const RenderSettings& s, LightKind light) {
  return light == LightKind::Point ? kPointLightFaceCount : s.cascades.count;
}

uint64_t shadowMapBytes(const MemoryReport& m, Technique technique) {
  if (!prefiltersChannels(technique)) return m.lightPass / 2;
  return m.technique + m.summedArea + m.auxiliary;
}

MemoryReport estimateMemory(const RenderSettings& s, LightKind light) {
  const int size = s.shadowMapSize;
  const ChannelLayout layout = channelLayout(s.technique, s.params);
  const int layers = shadowMapLayers(s, light);
  const uint64_t cascades = uint64_t(layers);
  MemoryReport m;
  m.lightPass = lightPassBytes(size, s.msaaSamples) * cascades;
  // PCF and the hard test read the light pass's depth: no channel texture (ChannelShape).
  if (prefiltersChannels(s.technique)) {
    m.technique = channelTextureBytes(layout, size, size, channelLevelsFor(s) > 1) * cascades;
  }
  if (buildsSummedAreaTable(s)) {
    const SummedAreaSizes sat = summedAreaSizes(layout.channels * layers, size);
    m.summedArea = sat.extremes + sat.stats + sat.sums;
  }
  if (blursIntoScratch(s)) m.scratch = channelTextureBytes(layout, size, size, false) * cascades;
  if (buildsZmaxPyramid(s)) {
    const ChannelLayout r32f{1, 1, 1, StorageFormat::Float32};
    m.auxiliary += channelTextureBytes(r32f, size, size, true) * cascades;
  }
  if (placesLayersByLloyd(s)) {
    m.auxiliary += lloydSampleBytes(size) * cascades + lloydRowCountBytes(size, layers) +
                   lloydGroupSumBytes(size, layers) + sizeof(shaders::LloydState);
  }
  m.frame = frameBytes(s.width, s.height, writesDiagnostics(s), s.lookupInputs);
  if (fitsDepthBounds(s)) m.frame += depthBoundsBytes(s.width, s.height);
  return m;
}

std::vector<PlannedTexture> plannedTextures(const RenderSettings& s, LightKind kind) {
  const int size = s.shadowMapSize;
  const ChannelLayout layout = channelLayout(s.technique, s.params);
  const int levels = channelLevelsFor(s);
  const bool ms = s.msaaSamples > 1;
  const int cascades = shadowMapLayers(s, kind);
  const GLenum light = ms ? GL_PROXY_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_PROXY_TEXTURE_2D_ARRAY;
  // Each of the two targets, every cascade.
  const uint64_t half = lightPassBytes(size, s.msaaSamples) / 2 * uint64_t(cascades);
  std::vector<PlannedTexture> t{
      {"light-pass depth", light, GL_R32F, 1, size, size, cascades, s.msaaSamples, half},
      {"light-pass depth buffer", light, GL_DEPTH_COMPONENT32F, 1, size, size, cascades,
       s.msaaSamples, half},
  };
  if (prefiltersChannels(s.technique)) {
    t.push_back({"channel texture", GL_PROXY_TEXTURE_2D_ARRAY, internalFormat(layout), levels, size,
                 size, layout.layers * cascades, 1,
                 channelTextureBytes(layout, size, size, levels > 1) * uint64_t(cascades)});
  }
  if (blursIntoScratch(s)) {
    t.push_back({"blur scratch texture", GL_PROXY_TEXTURE_2D_ARRAY, internalFormat(layout), 1, size,
                 size, layout.layers * cascades, 1,
                 channelTextureBytes(layout, size, size, false) * uint64_t(cascades)});
  }
  if (buildsZmaxPyramid(s)) {
    const ChannelLayout r32f{1, 1, 1, StorageFormat::Float32};
    t.push_back({"Z-max pyramid", GL_PROXY_TEXTURE_2D_ARRAY, GL_R32F, mipLevelCount(size, size),
                 size, size, cascades, 1,
                 channelTextureBytes(r32f, size, size, true) * uint64_t(cascades)});
  }
  const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
  for (const FrameTarget& target : kFrameTargets) {
    if (!allocates(target, writesDiagnostics(s), s.lookupInputs)) continue;
    t.push_back({target.what, GL_PROXY_TEXTURE_2D, target.format, 1, s.width, s.height, 1, 1,
                 pixels * uint64_t(target.bytesPerPixel)});
  }
  std::stable_sort(t.begin(), t.end(), [](const PlannedTexture& a, const PlannedTexture& b) {
    return a.bytes > b.bytes;
  });
  return t;
}

std::string sceneBufferShortfall(uint64_t vertices, uint64_t indices, std::string_view device) {
  bool software = false;
  for (std::string_view name : {"llvmpipe", "softpipe"}) {
    software |= device.find(name) != std::string_view::npos;
  }
  if (!software) return {};
  const struct {
    const char* what;
    uint64_t count;
    uint64_t size;
  } buffers[] = {{"vertices", vertices, sizeof(Vertex)}, {"indices", indices, sizeof(uint32_t)}};
  for (const auto& b : buffers) {
    const uint64_t bytes = b.count * b.size;
    if (bytes <= kSoftwareRasterizerMaxBufferBytes) continue;
    return "its " + std::to_string(b.count) + " " + b.what + " take " + std::to_string(bytes) +
           " bytes in one buffer (" + std::to_string(b.size) + " each), and " +
           std::string(device) + " draws from buffers of at most " +
           std::to_string(kSoftwareRasterizerMaxBufferBytes) +
           " bytes (signed 32-bit offsets; it crashes beyond)";
  }
  return {};
}

}  // namespace penumbra::gl
