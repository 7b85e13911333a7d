// The OpenGL 4.5 shadow renderer: light pass -> encode -> prefilter (blur, mips or summed-area
// table) -> camera pass, for any technique, one shadow map or cascades, with per-pass GPU times
// and exact memory. It lives across frames: the scene is uploaded once, each pass keeps its
// resources while the settings that shape them stay the same, and one call renders one frame.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "penumbra/cascades.h"
#include "penumbra/filter_mode.h"
#include "penumbra/filters.h"
#include "penumbra/image.h"
#include "penumbra/layer_placement.h"
#include "penumbra/scene.h"
#include "penumbra/shadow_lookup.h"
#include "penumbra/storage_format.h"
#include "penumbra/technique.h"

namespace penumbra::gl {

class Context;

using penumbra::FilterMode;  // penumbra/filter_mode.h

enum class Overlay {
  None,
  Cascades,  // tints each pixel by its cascade (blended in the blend band)
};

// The largest kernel radius the fused prefilter's tile holds (RenderSettings::fusePrefilter):
// its shared memory, (2r + 16)^2 + 16 (2r + 16) RGBA32F texels, stays within 32 KiB, the least
// GL 4.5 guarantees (GL_MAX_COMPUTE_SHARED_MEMORY_SIZE).
inline constexpr int kMaxFusedBlurRadius = 10;

// The images a frame reads back into its RenderResult (RenderSettings::readBack), as bits. Each
// read waits for the frame and copies a whole frame to the CPU; an image not read stays empty.
// The lookup's inputs are read only where the frame writes them (RenderSettings::lookupInputs).
namespace frame_image {
inline constexpr unsigned kColor = 1u << 0;
inline constexpr unsigned kVisibility = 1u << 1;
inline constexpr unsigned kDiagnostic = 1u << 2;  // and ESM's failure rate, counted on it
inline constexpr unsigned kLookup = 1u << 3;
inline constexpr unsigned kReceiverPlane = 1u << 4;
inline constexpr unsigned kUvDerivatives = 1u << 5;
inline constexpr unsigned kCascades = 1u << 6;
inline constexpr unsigned kNone = 0u;
inline constexpr unsigned kAll = (1u << 7) - 1u;
}  // namespace frame_image

struct RenderSettings {
  Technique technique = Technique::Vsm;
  TechniqueParams params = defaultTechniqueParams();
  int shadowMapSize = 1024;                      // texels per side, [16, GL_MAX_TEXTURE_SIZE]
  int msaaSamples = 1;                           // 1 (off), 2, 4 or 8, at most GL_MAX_SAMPLES
  BlurSpec blur{BlurKernel::Gaussian, 2, 1.0f};  // prefilter; radius 0 = none. With the
                                                 // summed-area filter the radius is the box minimum
  FilterMode filter = FilterMode::Trilinear;
  // Encode and both blur axes in one dispatch over a shared-memory tile where it gives the same
  // bits (32-bit float channels, no MSAA, kernels up to kMaxFusedBlurRadius: docs/renderer.md).
  // Off by default: on the 2026-12-04 llvmpipe machine it took 6-21x its minimal kernels, where
  // the separate passes took about 1-1.5x theirs (docs/results/passes-llvmpipe-2026-12-04.md);
  // bench --passes times both, so a device where the tile wins can show it.
  bool fusePrefilter = false;
  int anisotropy = 16;  // [1, 16], used by the anisotropic filter
  int width = 960;      // frame size in pixels, [1, GL_MAX_TEXTURE_SIZE]
  int height = 540;
  float normalOffsetTexels = 0.0f;  // normal-offset bias in shadow-map texels, [0, 10]
  float ambient = 0.2f;             // ambient share of the shading, [0, 1]
  // Cascades (directional lights); count 1 is one map fitted to the scene. The prefilter's
  // kernel is the blur above in cascade 0 and the same world size in every other cascade.
  CascadeSettings cascades;
  Overlay overlay = Overlay::None;
  // Whether a technique's frame writes and reads back the lookup's inputs (RenderResult::lookup,
  // receiverPlane, uvDerivatives, cascades): what the CPU twin, the lit-surface mask and the
  // diagnostics read (compare, the viewer's views). Off, the camera pass compiles them out and
  // allocates four targets fewer; on llvmpipe that took the pass from 2.0x its minimal lookup
  // to 1.6x (docs/results/passes-llvmpipe-2026-12-05.md). Reference frames always write them.
  bool lookupInputs = false;
  // Which images the frame reads back (frame_image bits). A frame that reads neither the
  // visibility nor the diagnostic, and writes no lookup inputs, draws its colour alone: the
  // camera pass compiles the other targets out (on llvmpipe EVSM4's pass went from 1.26-1.30x
  // its minimal lookup to 1.16-1.18x, docs/results/passes-llvmpipe-2026-12-06-diagnostics.md).
  // A frame that reads none and is not timed has no glFinish and no read-back, and waits for
  // nothing where the GPU keeps a frame's pace: the cascades' fitted depth bounds are the
  // previous frame's (a frame late, as real-time SDSM runs), LVSM's Lloyd placement stays on
  // the GPU.
  // Reference frames also read their visibility, and where the CPU completes pixels the colour,
  // diagnostic and lookup's inputs it completes them from (a supersampled reference returns only
  // the colour, visibility and diagnostic asked for, averaged).
  unsigned readBack = frame_image::kAll;
  // Whether the frame times its passes (RenderResult::gpuTimes, wallTimes): each pass between
  // glFinish calls, which keep a GPU from overlapping the passes. Off: no wait inside the frame,
  // and no times (both absent).
  bool timing = true;
};

// Where one frame is seen from and lit from.
struct FrameView {
  Camera camera;
  Light light;
  // The camera the cascades are fitted to, when it is not `camera`: holding the view still while
  // the cascades follow a moving camera shows (and measures) exactly what the shadow maps do,
  // like engines' frozen-shadow-camera debug views. Unset: `camera`.
  std::optional<Camera> shadowCamera = std::nullopt;
};

// Why a device has no GPU times (Renderer::timerQueriesMeasureExecution false), as the reports
// and the viewer say it.
inline constexpr const char* kNoGpuTimesReason =
    "this device is a software rasteriser, whose timer queries time the command submission, not "
    "the execution";

struct PassTimes {  // milliseconds per pass
  double light = 0.0;
  double encode = 0.0;
  double prefilter = 0.0;  // separable blur; with a fused prefilter, encode and blur (encode 0)
  double mipsOrSat = 0.0;  // mip chain or summed-area table
  double auxiliary = 0.0;  // ESM's Z-max pyramid or LVSM's Lloyd split placement
  double camera = 0.0;
  double depthBounds = 0.0;  // the depth-bounds pre-pass and reduction (cascades fitted to depth)
  double total() const {
    return light + encode + prefilter + mipsOrSat + auxiliary + camera + depthBounds;
  }
};

struct MemoryReport {       // exact bytes allocated
  uint64_t lightPass = 0;   // linear depth target and depth buffer (times MSAA samples)
  uint64_t technique = 0;   // the technique's channel texture, mips included (PCF, hard: none)
  uint64_t summedArea = 0;  // summed-area table sums and statistics
  uint64_t scratch = 0;     // the blur's intermediate texture
  uint64_t auxiliary = 0;   // ESM's Z-max pyramid (R32F, mips) or LVSM's Lloyd samples
  uint64_t frame = 0;       // camera-pass targets (and the depth-bounds pass's)
  // The scene's vertex, index and texture storage (mips included): it depends on the scene, not
  // on the settings, so estimateMemory leaves it 0.
  uint64_t geometry = 0;
  uint64_t total() const {
    return lightPass + technique + summedArea + scratch + auxiliary + frame + geometry;
  }
};

// What a technique's shadow map keeps between frames, as the papers count a technique's memory
// and `compare` and the paper bench report it: the channels and their mips, the summed-area
// table, ESM's Z-max pyramid or LVSM's Lloyd samples; for PCF and the hard test, which have no
// channel texture, the light pass's R32F depth their lookup reads (half of its two targets). Not
// the blur's scratch, a transient whose need depends on how the prefilter runs (none fused).
uint64_t shadowMapBytes(const MemoryReport& memory, Technique technique);

// The bytes render() allocates for these settings (its RenderResult::memory, geometry aside),
// computed up front from the same formulas; Renderer::validate refuses settings whose
// allocations do not fit.
// A point light's maps are six layers (one per face), a directional light's one per cascade.
MemoryReport estimateMemory(const RenderSettings& settings,
                            LightKind light = LightKind::Directional);

struct RenderResult {
  // RGBA in [0,1], row 0 at the top: linear light, as the camera pass shades it (sRGB textures
  // are decoded on sampling). Not display-ready: writeColorPng encodes it to sRGB.
  Image color;
  Image visibility;  // one float channel in [0,1], row 0 at the top
  // Per pixel, row 0 at the top: -1 where nothing is drawn; ESM: 1 where classification failed
  // (and its `fallback` parameter's PCF shaded it), else 0; LVSM and the power CDF: the
  // receiver's layer index; else 0.
  Image diagnostic;
  // ESM with a classifier, in a frame that reads the diagnostic back: failing pixels as a share
  // of drawn pixels, in percent; else 0.
  double failureRatePercent = 0.0;
  // The parameters used, with LVSM's splits as placed for this frame. Lloyd's splits are placed
  // on the GPU and read back only by a frame that waits anyway (reads an image back or is
  // timed); in one that reads nothing back and is not timed their interior entries are NaN.
  TechniqueParams params;
  // Per pixel, row 0 at the top: the shadow-map lookup (u, v, receiver depth, w) with w = 1 inside
  // the shadow map on a surface facing the light (N.L > 0.05: where the shadow test decides the
  // shading), 0.5 inside but facing away or grazing, 0 outside; and the receiver plane's depth
  // gradient per shadow-map texel. These four are empty unless RenderSettings::lookupInputs (or
  // a reference frame at supersample 1).
  Image lookup;
  Image receiverPlane;
  Image uvDerivatives;  // per pixel, row 0 at the top: dFdx(uv) and dFdy(uv), the footprint
  // Per pixel, row 0 at the top: the cascade whose lookup (uv, receiver plane, derivatives
  // above) decides, -1 outside every map; and the blend weight of the next cascade.
  Image cascades;
  CascadeFrame cascadeFrame;           // the frame's cascades (count 1: one map, identity box)
  std::vector<BlurSpec> cascadeBlurs;  // the prefilter kernel of each cascade
  DepthRange depthBounds;              // the depth range the cascades split
  // GL_TIME_ELAPSED queries of a timed frame (RenderSettings::timing) where they time execution
  // (timerQueriesMeasureExecution); absent otherwise: a software rasteriser's queries see only
  // submission, so what they read is not a GPU time and is not reported as one.
  std::optional<PassTimes> gpuTimes;  // kNoGpuTimesReason says why where absent
  // Wall clock between glFinish calls, what llvmpipe really spends; absent where the frame was
  // not timed (RenderSettings::timing): a 0 would read as a pass that cost nothing.
  std::optional<PassTimes> wallTimes;
  MemoryReport memory;
  // Whether encode and blur ran as one dispatch per map (RenderSettings::fusePrefilter).
  bool fusedPrefilter = false;
};

// Whether a kernel of this radius runs as the fused prefilter under these settings
// (RenderSettings::fusePrefilter): a blur, 32-bit float channels, one light-pass sample, no
// summed-area table, radius in [1, kMaxFusedBlurRadius]. A frame fuses when every map's does.
bool fusesPrefilter(const RenderSettings& settings, int radius);

// Pixel (x, y)'s lookup inputs (its cascade's uv, receiver depth, footprint and receiver
// plane) as the CPU twin (penumbra/shadow_lookup.h) takes them. Throws Error for a frame without
// them (rendered without RenderSettings::lookupInputs).
LookupPixel lookupPixelAt(const RenderResult& result, int x, int y);
// The same lookup in the next cascade (cascade + 1), for the blend band: the point on the light's
// plane, its footprint and its receiver plane in that cascade's map (shared/cascade_selection.h).
LookupPixel lookupPixelInNextCascade(const LookupPixel& pixel, const CascadeFrame& cascades,
                                     int cascade, int shadowMapSize);

class Renderer {
 public:
  // Needs a current GL 4.5 core context (HeadlessContext, or CurrentContext for a window's);
  // compiles shader variants on first use.
  explicit Renderer(const Context& context);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Checks settings against their ranges and this GL's limits, memory included: every texture
  // must pass the GL's proxy test and the total (estimateMemory) must fit the free GPU memory
  // (GL_NVX_gpu_memory_info, GL_ATI_meminfo) or, where the GL does not say, half the machine's
  // RAM. Throws Error saying which and why, and for memory the largest shadow-map size that fits.
  // `light`: the kind of light the frame has (a point light's six faces take six layers).
  void validate(const RenderSettings& settings, LightKind light = LightKind::Directional) const;
  // Refuses a light size out of range, and soft shadows (Light::size > 0) with cascades or, for
  // the filterable techniques, with a filter that cannot widen (point, bilinear). render() calls
  // it with the frame's light.
  static void checkSoftShadows(const RenderSettings& settings, const Light& light);

  // Caps the memory validate() lets one render plan for, below what the GL offers (several
  // renderers sharing a device, tests). 0 removes the cap.
  void limitMemory(uint64_t bytes);

  // Uploads the scene's geometry and materials once; frames then draw it from any view.
  void setScene(const Scene& scene);
  // One frame of the current scene.
  RenderResult render(const RenderSettings& settings, const FrameView& view);
  // One frame from the scene's own camera and light; uploads the scene first unless its content
  // is the one already uploaded.
  RenderResult render(const Scene& scene, const RenderSettings& settings);

  // The filtered reference (docs/reference.md): per pixel, the exact PCF of the raw depth under
  // the effective kernel of `settings` (its blur, filter mode and anisotropy) in the pixel's
  // cascade (blended like the technique in the blend band), evaluated at supersample x
  // supersample sub-pixel positions and averaged (1: the filtered reference itself; 4 or more:
  // the supersampled ground truth). MSAA is off for the reference. Reads back the images of
  // settings.readBack; supersampled, only its colour and diagnostic, averaged, and always the
  // visibility.
  RenderResult renderReference(const RenderSettings& settings, const FrameView& view,
                               int supersample);
  RenderResult renderReference(const Scene& scene, const RenderSettings& settings, int supersample);

  // The area-light reference (docs/reference.md) of view.light, a light with a size: per pixel,
  // the mean of the hard shadow tests (receiver plane, no bias beyond rounding) of `samples`
  // shadow maps rendered from stratified points on the light's disk (penumbra/area_light.h), at
  // supersample x supersample sub-pixels averaged (1: the reference; 4 or more: its supersampled
  // ground truth). Colour is each sample light's shading averaged. lookup, receiverPlane,
  // uvDerivatives and cascades are those of the light's centre (one more render, the last, so
  // readDepthMap reads the centre's map). One map only (no cascades), MSAA off.
  RenderResult renderAreaLightReference(const RenderSettings& settings, const FrameView& view,
                                        int samples, int supersample);

  // A cascade's light-pass linear depth (sample 0 under MSAA) of the last render, row 0 at the
  // bottom.
  Image readDepthMap(int cascade = 0) const;
  // The last camera pass's depth buffer, row 0 at the top: window depth in [0,1] through the
  // camera's projection (clipFromView), 1 where nothing is drawn — at the reference's
  // supersampled size after a supersampled reference. The ray-traced truth's surfaces are
  // matched against it (truth::matchRasterisedSurfaces).
  Image readCameraDepth() const;
  // Every light-pass sample of a cascade's depth (MSAA), one image channel per sample.
  Image readDepthSamples(int cascade = 0) const;
  // A cascade's technique channels at a mip level after the last render (encoded and
  // prefiltered), one image channel per technique channel, row 0 at the bottom. PCF and the hard
  // test have no channel texture: their one channel is the light pass's depth as their lookup
  // reads it (the nearest sample under MSAA), level 0 only.
  Image readChannels(int level, int cascade = 0) const;
  int channelMipLevels() const;
  // bench --passes' yardstick for the camera pass: the last frame's view drawn again with the
  // least lookup of its technique (passes/minimal_lookup.frag: one map, one filtered fetch per
  // channel layer, or with the summed-area filter each read channel's box mean from the table,
  // the reconstruction, Lambert, one RGBA8 target), after render() of one map. esmFallback: with
  // ESM's threshold classification and its fallback as well, where the pass has them.
  // The draw's milliseconds: a GPU timer query where they measure execution, else wall clock.
  // Throws for PCF and the hard test, which prefilter nothing (no channels to fetch).
  double timeMinimalLookup(bool esmFallback = false);
  // bench --passes: the last frame's camera pass drawn again (the same program, inputs and
  // targets), so that the pass and its minimal lookup can be timed alternately several times a
  // frame. Its milliseconds, as timeMinimalLookup's; after render() of a technique's frame.
  double timeCameraPass();
  // bench --passes: the last frame's encode pass dispatched again (the same program, depth and
  // channel texture, whose level 0 then holds the unfiltered channels until the next render),
  // so that the pass and its copy can be timed alternately several times a frame. Its
  // milliseconds, as timeMinimalLookup's; after render() or filterDepthMap() whose prefilter ran
  // as separate passes (not fused).
  double timeEncodePass();
  Image readCameraColor() const;         // the camera pass's colour target as its last draw left it
  Image readMinimalLookupColor() const;  // its picture: RGBA in [0,1], linear, row 0 at the top
  int minimalLookupDraws(bool esmFallback) const;  // its draws so far, with or without the fallback
  // Bytes of the technique's channel texture measured from the GL object itself (each level's
  // size and component bit depths), to check MemoryReport::technique against; 0 for PCF and the
  // hard test, which have none.
  uint64_t measuredChannelTextureBytes() const;
  // The camera pass's render targets of the last frame, measured on the GL objects the same way
  // (RenderResult::memory.frame is computed from the settings, as estimateMemory's).
  uint64_t measuredFrameBytes() const;
  // The Z-max pyramid level of the last ESM render with the zmax classifier, row 0 at the bottom.
  Image readZmaxLevel(int level) const;
  // The Lloyd samples (second-occluder depth, weight) of the last LVSM render with Lloyd placement
  // that weigh anything (weight > 0: the ones a Lloyd step reads), row by row as
  // secondOccluderSamples lists them.
  std::vector<SplitSample> readSplitSamples() const;

  // Runs encode and prefilter on a given depth map (row 0 at the bottom) without a scene:
  // the path the GPU-parity tests compare with the CPU reference filters.
  void filterDepthMap(const Image& depth, const RenderSettings& settings);
  // The summed-area box mean the camera pass would compute, for parity tests.
  double summedAreaBoxMean(int x0, int y0, int x1, int y1, int channel) const;
  // The quantisation the GPU derived for a channel of the summed-area table from its extremes
  // (shared/summed_area.h), for parity tests.
  struct SummedAreaChannelStats {  // lib/summed_area.glsl SatChannelStats, as the GPU stores it
    double centre, step;
  };
  static_assert(sizeof(SummedAreaChannelStats) == 16, "std430 SatChannelStats: two doubles");
  SummedAreaChannelStats summedAreaQuantisation(int channel) const;

  std::string deviceDescription() const;
  // False on software rasterisers (llvmpipe, softpipe), whose GL_TIME_ELAPSED queries see only
  // command submission: there RenderResult::wallTimes is what a pass costs.
  bool timerQueriesMeasureExecution() const;
  // How this device rounds floats stored to fp16 textures, measured once at construction.
  HalfRounding halfFloatRounding() const;

  struct State;  // GL objects; defined in src/gl/renderer_state.h for the pass files

 private:
  void checkMemory(const RenderSettings& settings, LightKind light) const;

  RenderResult renderFrame(const RenderSettings& settings, const FrameView& view, bool reference);
  void completeReferenceOnCpu(RenderResult& full) const;

  std::unique_ptr<State> state_;
};

}  // namespace penumbra::gl
