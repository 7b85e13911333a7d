// The true shadow (docs/reference.md, "Ray-traced truth"): the visibility of the light from the
// surface each sub-pixel sees, by ray tracing the scene's triangles with Intel Embree 3 — not
// from any shadow map, so it is the same whatever the shadow-map size, kernel or technique.
//
// Per sub-pixel (the S x S positions of the supersampled ground truth): the camera ray's first
// hit, then occlusion rays to the light — one for a hard directional, spot or point light; for a
// light with a size, N stratified points of its disk or sphere with the area-light reference's
// weights (penumbra/area_light.h). Shadow rays start at the hit moved off its triangle by the
// integer-ulp offset of Wächter and Binder (surface_offset.h): no bias to tune.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "penumbra/image.h"
#include "penumbra/scene.h"

namespace penumbra::truth {

// Light samples per ray-traced pixel for a light with a size: side^2, side in [1, 64].
// 4096 is for convergence studies; a hard light always takes one ray.
inline constexpr int kMaxTrueShadowLightSamples = 4096;
inline constexpr int kDefaultTrueShadowLightSamples = 64;
// Throws Error naming the valid counts unless `count` is side^2 with side in [1, 64].
void checkTrueShadowLightSamples(int count);

// A scene's triangles in an Embree BVH, built once and traced for every frame, light and
// technique (the geometry is what matters; camera and light are per trace). Alpha-masked
// materials are tested by filter functions with the light pass's alpha texture and cutoff;
// single-sided meshes are culled from behind for camera rays (as the camera pass culls them) and
// cast shadows from both sides (as the light pass draws them).
class RayScene {
 public:
  // Keeps a copy of what the traces need (positions, texture coordinates, materials, textures),
  // so `scene` need not outlive it. Throws Error when Embree fails (its message included).
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  size_t triangleCount() const;
  double buildSeconds() const;  // wall time of the BVH build (rtcCommitScene)
  // Opaque to callers: the Embree handles and the copies the filter functions read.
  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

struct TrueShadowRequest {
  Camera camera;
  Light light;
  // The camera's near and far planes come from them (cameraNear, cameraFar), as the rasteriser's.
  ViewBounds viewBounds;
  int width = 480;     // output pixels
  int height = 270;
  int supersample = 4;  // sub-pixels per side, [1, 8]: those of the supersampled ground truth
  // Light samples per sub-pixel for a light with a size (checkTrueShadowLightSamples); ignored
  // for a hard light.
  int lightSamples = kDefaultTrueShadowLightSamples;
  float ambient = 0.2f;  // the camera pass's ambient share (RenderSettings::ambient), for the shaded image
};

struct TrueShadow {
  // Per output pixel, row 0 at the top: the mean over the sub-pixels whose camera ray hit a
  // surface of the share of the light they see (0 to 1); -1 where no sub-pixel hit anything.
  Image visibility;
  // RGBA, linear light, row 0 at the top: Lambert + ambient shading of each hit with the
  // camera pass's formula (shared/shading.h) and this visibility, box-averaged; sky where none.
  Image color;
  // Per output pixel: 1 where the light reaches every sub-pixel's surface point as the renderer
  // lights it: its triangle faces the light's centre beyond grazing (shaders::kGrazingCosine)
  // by its own plane, and a spot light's cone holds it; 0 where one is not reached. Such pixels
  // are the shadow terminator of a tessellated surface (the smoothly interpolated normal the
  // camera pass shades with still faces the light, the flat triangle does not: the truth is
  // dark, a shadow map's normal offset lights it), pixels straddling the edge between a lit and
  // an unlit face (some sub-pixels on each), and ground outside a spot's cone inside its map's
  // square; compare leaves them out (and counts them) rather than score an error there.
  Image reachedByLight;
  // Per sub-pixel (width x supersample by height x supersample, row 0 at the top): the view
  // depth of the camera ray's first hit (distance along the camera's axis), +infinity on a miss:
  // what matchRasterisedSurfaces compares with the rasteriser's depth.
  Image subPixelViewDepth;
  uint64_t cameraRays = 0;
  uint64_t shadowRays = 0;
  double seconds = 0.0;  // wall time of the trace
};

// Throws Error for out-of-range sizes or sample counts, before tracing.
TrueShadow traceTrueShadow(const RayScene& scene, const TrueShadowRequest& request);

// For a trace off the caller's thread (the viewer's): progress, and a stop it checks between
// output rows. Both optional.
struct TraceControl {
  std::function<bool()> stopRequested;  // true: the trace ends at its workers' next row
  std::atomic<int>* rowsDone = nullptr;  // counts finished output rows (in any order)
};
// As above; nothing once stopRequested() said true.
std::optional<TrueShadow> traceTrueShadow(const RayScene& scene, const TrueShadowRequest& request,
                                          const TraceControl& control);

// Where the ray-traced frame and a rasterised one see the same surfaces: the rasteriser's depth
// buffer of the same camera at the same sub-pixels (window depth in [0,1], 1 where nothing is
// drawn, width x supersample by height x supersample, row 0 at the top) against the traced view
// depths. A pixel is matched when every sub-pixel's two depths agree within the rasteriser's
// precision (kSurfaceMatchTolerance) or both miss; the others — silhouettes, where one sample
// lands on another surface — are excluded from every measurement and counted.
struct SurfaceMatch {
  Image matched;  // per output pixel: 1 matched, 0 excluded
  int excludedPixels = 0;       // pixels where some sub-pixel sees different surfaces
  int mismatchedSubPixels = 0;  // sub-pixels that do
};
// Relative view-depth difference below which two sub-pixels see the same surface: the camera
// pass's fp32 window depth resolves view depth to about 1.5e-4 relative at the far plane of a
// camera framing the scene (cameraNear scales with it), and a sub-pixel that lands on another
// surface jumps by more — a silhouette's depth step.
inline constexpr float kSurfaceMatchTolerance = 1e-3f;
SurfaceMatch matchRasterisedSurfaces(const TrueShadow& trace, const Image& rasterWindowDepth,
                                     const TrueShadowRequest& request);

// The pixels a rasterised frame is measured on against the truth (compare, the viewer): those
// whose shading its shadow test decides (`shadowTestCoverage`, litSurfaceMask of its lookup),
// left out where a sub-pixel sees another surface than the rasterised frame or none
// (kExcludedSurface), or where the light does not reach a sub-pixel's surface as the renderer
// lights it (kExcludedUnlit, TrueShadow::reachedByLight).
inline constexpr float kExcludedSurface = 1.0f;
inline constexpr float kExcludedUnlit = 2.0f;
struct MeasuredPixels {
  Image coverage;   // 1: measured
  Image exclusion;  // why a covered pixel is not: 0 (it is, or it is not covered) or a kExcluded*
  int excludedPixels = 0;    // kExcludedSurface
  int unlitPixels = 0;  // kExcludedUnlit
};
MeasuredPixels measuredPixels(const Image& shadowTestCoverage, const TrueShadow& trace,
                              const SurfaceMatch& match);

// Embree's own description of the build (version, ISA), for reports.
std::string embreeDescription();

}  // namespace penumbra::truth
