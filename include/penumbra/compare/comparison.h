// Measuring techniques against the references (docs/reference.md): every technique is rendered
// along the scene's camera path, next to the filtered reference of the same effective kernel
// and, for the first frame, the supersampled ground truth and the ray-traced true shadow (the
// primary reference: the ranking is by it); metrics come from penumbra/metrics.h. The report
// writer (report.h) turns the result into files.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/area_light.h"
#include "penumbra/depth_distribution.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/metrics.h"
#include "penumbra/truth/true_shadow.h"

namespace penumbra::compare {

// The primary reference: the ray-traced true shadow of frame 0 (penumbra/truth/true_shadow.h),
// or none (the filtered reference ranks, as before the truth existed).
enum class TruthKind { RayTraced, None };
// "raytraced", "none"; parseTruthKind throws Error listing the valid names.
std::string_view truthKindName(TruthKind kind);
TruthKind parseTruthKind(std::string_view name);

struct ComparisonRequest {
  std::string scene = "backyard";  // a built-in scene's name or a scene file (loadScene)
  SceneLoadOptions sceneLoad;      // what loading a scene file may take
  SceneOverrides view;             // camera and light set from outside the scene
  std::vector<Technique> techniques;
  gl::RenderSettings settings;  // shared by every technique (its `technique` field is ignored)
  int supersample = 4;          // ground-truth sub-pixels per side, [1, 8]
  int pathFrames = 4;           // camera-path frames for flicker, [2, 32]
  double tau = 0.05;            // leak / over-darkening threshold on visibility, (0, 1)
  // Give PCF the kernel of the prefilter (box blur: box x bilinear, or box for point lookups;
  // Gaussian blur: Gaussian, the blur's sigma; the blur's radius), no bias and the receiver-plane
  // test, so that it is the filtered reference itself where the lookup allows (point, bilinear).
  // Off when the user set any PCF parameter: PCF then runs with `settings.params.pcf` as given
  // and the report says it is not matched.
  bool matchPcfKernel = true;
  // With a light size (view.lightSize or the scene's light): the area-light reference's point
  // samples per light disk (penumbra/area_light.h), replacing the filtered reference; PCF is then
  // PCSS, not matched.
  int areaLightSamples = kMinAreaLightSamples;
  TruthKind truth = TruthKind::RayTraced;
  // The truth's light samples per sub-pixel for a light with a size
  // (truth::checkTrueShadowLightSamples); a hard light takes one ray.
  int truthLightSamples = truth::kDefaultTrueShadowLightSamples;
};

// Shimmer (frameToFrameChange) of one technique with cascades fitted both ways, measured side by
// side: the cascades follow the camera path while the view holds at its first camera, so every
// change of the picture is the shadow maps' own (docs/cascades.md).
// The shadow camera's turn per frame on the shimmer path (on top of the scene's camera path).
inline constexpr float kShimmerTurnDegrees = 0.25f;

struct CascadeShimmer {
  double stabilized = 0.0;
  double tight = 0.0;
};

struct TechniqueResult {
  Technique technique = Technique::Vsm;
  TechniqueParams params;           // as used (LVSM splits placed for frame 0)
  VisibilityErrors filtered;        // frame 0 against the filtered reference
  VisibilityErrors groundTruth;     // frame 0 against the supersampled ground truth
  double flicker = 0.0;             // along the camera path, beyond the reference's own
  // Cascaded directional lights only: shimmer with stabilised and with tight cascades.
  std::optional<CascadeShimmer> shimmer;
  double failureRatePercent = 0.0;  // ESM classification; 0 otherwise
  // The last frame's times (warm: no first-use shader compilation); GPU times only where the
  // device's timer queries time execution (gl::RenderResult::gpuTimes).
  std::optional<gl::PassTimes> gpuTimes;
  gl::PassTimes wallTimes;
  gl::MemoryReport memory;
  Image color;  // frame 0, row 0 at the top
  Image visibility;
  Image error;  // visibility - filtered reference, 0 where uncovered
  // Against the ray-traced truth (TruthKind::RayTraced): frame 0's errors over the truth's
  // pixels (TruthResult::coverage) — the total error, whose parts are the filtering part
  // (`filtered`: the technique against the filtered reference) and the sampling part common to
  // all (TruthResult::referenceVsTruth) — and its heat map.
  std::optional<VisibilityErrors> truth;
  // The filtering part's RMSE over the truth's pixels, so that the decomposition's three RMSEs
  // are over one set of pixels (`filtered` covers every lit-surface pixel).
  double filteringRmseOnTruthPixels = 0.0;
  Image truthError;  // visibility - truth, 0 outside TruthResult::coverage
};

// The ray-traced true shadow of frame 0 and the shadow-map references measured against it.
struct TruthResult {
  Image visibility;  // per pixel, -1 where no surface (truth::TrueShadow::visibility)
  Image color;
  // The pixels measured against the truth and why the other covered ones are not
  // (truth::measuredPixels): a sub-pixel sees another surface than the rasterised frame, or the
  // light does not reach it (truth::TrueShadow::reachedByLight).
  Image coverage;
  Image exclusion;  // truth::kExcludedSurface, truth::kExcludedUnlit or 0
  int excludedPixels = 0;  // covered pixels left out: a sub-pixel sees another surface
  int mismatchedSubPixels = 0;
  // Covered pixels left out where the light does not reach a sub-pixel's surface as the
  // renderer lights it (truth::TrueShadow::reachedByLight: the shadow terminator of a
  // tessellated surface, the edge of a lit and an unlit face, outside a spot's cone).
  int unlitPixels = 0;
  // Pixels the truth lights (>= 1 - tau) that the filtered (or area-light) reference darkens by
  // more than tau (docs/reference.md): its kernel spreading a shadow past a hard edge, its
  // receiver plane missing the curved neighbours of a surface. A technique lighter than the
  // reference there is nearer the truth, so the leak columns against the reference leave them
  // out: no technique is called leaking there.
  Image referenceTooDark;
  int referenceTooDarkPixels = 0;
  VisibilityErrors referenceVsTruth;    // the sampling part: the filtered reference's own error
  VisibilityErrors groundTruthVsTruth;  // the supersampled ground truth's
  int lightSamples = 1;  // per sub-pixel (1 for a hard light)
  size_t triangles = 0;
  double bvhSeconds = 0.0;
  double traceSeconds = 0.0;
  uint64_t cameraRays = 0;
  uint64_t shadowRays = 0;
};

struct ComparisonResult {
  // As rendered: overrides applied; its warnings are the loader's. Scenes without trouble spots
  // of their own get the regions of largest error (error_regions.h).
  Scene scene;
  ComparisonRequest request;
  std::string device;
  Image referenceColor;
  // True when the scene's light has a size: the references are the area-light reference and its
  // supersampled version (docs/reference.md), not the filtered reference.
  bool areaLight = false;
  Image referenceVisibility;    // the filtered (or area-light) reference, frame 0
  Image groundTruthVisibility;  // supersampled, frame 0
  Image coverage;               // 1 where the shadow test decides the shading (litSurfaceMask)
  std::optional<TruthResult> truth;  // absent with TruthKind::None
  std::vector<TechniqueResult> techniques;
  // Set when the reference and every technique have most lit surfaces in shadow
  // (mostlyShadowedWarning): the report says so above its ranking.
  std::optional<std::string> shadowedWarning;
  // The worst pixel over all techniques (against the filtered reference) and the depth
  // distribution of its reference kernel, shifted along the receiver plane so that the receiver
  // sits at `worstReceiverDepth`: what `penumbra curves` plots.
  std::string worstTechnique;
  int worstX = -1;
  int worstY = -1;
  float worstReceiverDepth = 0.0f;
  std::vector<DepthSample> worstRegion;
};

// Whether compare's PCF runs with the prefilter's kernel (pcfMatchingPrefilter): matching asked
// for and a light without size (under an area light PCF is PCSS with its own parameters).
bool matchesPcfKernel(const ComparisonRequest& request, bool areaLight);
// Whether that matched PCF is the filtered reference itself, so that its error is the
// reference's rounding and not a technique's: point or bilinear lookups (mip-mapped ones get the
// nearest PCF kernel) and a single-sampled light pass (under MSAA PCF tests the nearest of each
// texel's samples, the reference its single-sampled depth).
bool matchedPcfIsReference(const ComparisonRequest& request, bool areaLight);

// PCF parameters that make PCF the filtered reference of these settings' prefilter (box or
// Gaussian blur x the lookup) where the lookup allows: compare's matched PCF.
shaders::PcfParams pcfMatchingPrefilter(const gl::RenderSettings& settings);

// The frame's reference at `supersample` sub-pixels per side: the area-light reference when the
// light has a size (`areaLight`), else the filtered reference, of `request.settings`, reading
// back the images both `readBack` and the request's settings name (gl::frame_image; the
// area-light reference reads its own).
gl::RenderResult renderReferenceFor(const ComparisonRequest& request, gl::Renderer& renderer,
                                    const gl::FrameView& view, bool areaLight, int supersample,
                                    unsigned readBack = gl::frame_image::kAll);

// step: what is being done; done/total: steps so far and in all.
using Progress = std::function<void(int done, int total, const std::string& step)>;

// Checks everything a run will need (names, ranges, GL limits, every technique with the
// settings) and throws Error before anything is rendered or written.
void validateRequest(const ComparisonRequest& request, const gl::Renderer& renderer);

ComparisonResult runComparison(const ComparisonRequest& request, gl::Renderer& renderer,
                               const Progress& progress = {});

}  // namespace penumbra::compare
