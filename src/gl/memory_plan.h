// What a render allocates, derived from the settings alone. The allocation code takes its
// decisions and buffer sizes from here, the memory report its formulas, and Renderer::validate
// the up-front estimate it checks against what the GL can hold: one source for all three.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "penumbra/gl/renderer.h"

namespace penumbra::gl {

// Decisions of the passes.
int channelLevelsFor(const RenderSettings& settings);
bool blursIntoScratch(const RenderSettings& settings);
// Whether this frame's prefilter runs fused: every cascade's kernel does.
bool fusesPrefilter(const RenderSettings& settings, std::span<const BlurSpec> cascadeBlurs);
bool buildsSummedAreaTable(const RenderSettings& settings);
bool buildsZmaxPyramid(const RenderSettings& settings);
bool placesLayersByLloyd(const RenderSettings& settings);
bool fitsDepthBounds(const RenderSettings& settings);  // cascades split the visible depth range
// Whether the camera pass writes its visibility and diagnostic targets: when the frame reads
// either back, or writes the lookup's inputs (what reads those reads these too). Otherwise they
// are compiled out (camera.frag's DIAGNOSTICS) and not allocated.
bool writesDiagnostics(const RenderSettings& settings);

// Shadow-map layers: six faces for a point light, else one per cascade.
int shadowMapLayers(const RenderSettings& settings, LightKind light);

// Bytes of the allocations that are not channel textures (channel_layout.h has those).
uint64_t lightPassBytes(int shadowMapSize, int samples);  // R32F + D32F per sample
// The camera pass's targets: colour and depth; visibility and diagnostic when it writes them
// (writesDiagnostics, implied by lookupInputs); the lookup's four inputs when it writes them
// (RenderSettings::lookupInputs).
uint64_t frameBytes(int width, int height, bool diagnostics, bool lookupInputs);
// The depth-bounds pass: its D32F target, and the results of this frame's measurement and the
// previous frame's, which a frame that waits for nothing takes (depth_bounds_pass.h).
inline constexpr int kDepthBoundsMeasurementsInFlight = 2;
inline constexpr uint64_t kDepthBoundsBytesPerMeasurement = 8;  // the nearest and farthest bits
uint64_t depthBoundsBytes(int width, int height);
struct SummedAreaSizes {
  size_t extremes, stats, sums;  // two keys, {centre, step} and the 64-bit sums per channel
};
SummedAreaSizes summedAreaSizes(int channels, int shadowMapSize);
size_t lloydSampleBytes(int shadowMapSize);
// Lloyd's sums pass: its groups of sample rows (every cascade's rows in turn), and their sums.
unsigned lloydRowGroups(int shadowMapSize, int cascades);
size_t lloydGroupSumBytes(int shadowMapSize, int cascades);
size_t lloydRowCountBytes(int shadowMapSize, int cascades);

// One texture a render creates, as the GL's proxy test takes it.
struct PlannedTexture {
  std::string_view what;  // "channel texture", ...
  unsigned proxyTarget;   // GL_PROXY_TEXTURE_2D, _2D_ARRAY or _2D_MULTISAMPLE_ARRAY
  unsigned internalFormat;
  int levels = 1;
  int width = 0, height = 0, layers = 1, samples = 1;
  uint64_t bytes = 0;
};

// The textures of a render with these settings, largest first.
std::vector<PlannedTexture> plannedTextures(const RenderSettings& settings, LightKind light);

}  // namespace penumbra::gl
