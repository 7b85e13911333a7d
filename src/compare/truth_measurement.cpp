// Tracing a comparison's truth and measuring the references against it (truth_measurement.h).
#include "penumbra/compare/truth_measurement.h"

#include <atomic>
#include <mutex>
#include <utility>

namespace penumbra::compare {

TruthResult measureTruth(const truth::RayScene& rays, const ComparisonRequest& request,
                         const Scene& scene, const Camera& camera, const RasterisedFrame& frame,
                         const std::function<void(int done, int of)>& onRows) {
  truth::TrueShadowRequest trace;
  trace.camera = camera;
  trace.light = scene.light;
  trace.viewBounds = scene.viewBounds();
  trace.width = request.settings.width;
  trace.height = request.settings.height;
  trace.supersample = request.supersample;
  trace.lightSamples = scene.light.size > 0.0f ? request.truthLightSamples : 1;
  trace.ambient = request.settings.ambient;
  // A soft light's trace can take minutes (4096 samples per sub-pixel): its rows feed the
  // progress bar, one caller at a time.
  std::atomic<int> rowsDone{0};
  std::mutex reporting;
  truth::TraceControl control;
  control.rowsDone = &rowsDone;
  if (onRows) {
    control.stopRequested = [&] {
      const std::lock_guard<std::mutex> lock(reporting);
      onRows(rowsDone.load(), trace.height);
      return false;
    };
  }
  const truth::TrueShadow traced = *truth::traceTrueShadow(rays, trace, control);
  const truth::SurfaceMatch match =
      truth::matchRasterisedSurfaces(traced, frame.supersampledDepth, trace);

  TruthResult t;
  t.visibility = traced.visibility;
  t.color = traced.color;
  t.lightSamples = trace.lightSamples;
  t.triangles = rays.triangleCount();
  t.bvhSeconds = rays.buildSeconds();
  t.traceSeconds = traced.seconds;
  t.cameraRays = traced.cameraRays;
  t.shadowRays = traced.shadowRays;
  t.mismatchedSubPixels = match.mismatchedSubPixels;
  truth::MeasuredPixels measured = truth::measuredPixels(frame.coverage, traced, match);
  t.coverage = std::move(measured.coverage);
  t.exclusion = std::move(measured.exclusion);
  t.excludedPixels = measured.excludedPixels;
  t.unlitPixels = measured.unlitPixels;
  t.referenceTooDark = Image(trace.width, trace.height, 1, 0.0f);
  const float tau = float(request.tau);
  for (int y = 0; y < trace.height; ++y) {
    for (int x = 0; x < trace.width; ++x) {
      if (!(t.coverage.at(x, y) > 0.5f)) continue;
      const float truth = t.visibility.at(x, y);
      // The reference darkens a surface the geometry lights: its own error, not a leak of the
      // techniques that light it.
      if (truth >= 1.0f - tau && frame.referenceVisibility.at(x, y) < truth - tau) {
        t.referenceTooDark.at(x, y) = 1.0f;
        ++t.referenceTooDarkPixels;
      }
    }
  }
  t.referenceVsTruth =
      measureVisibilityErrors(frame.referenceVisibility, t.visibility, t.coverage, request.tau);
  t.groundTruthVsTruth =
      measureVisibilityErrors(frame.groundTruthVisibility, t.visibility, t.coverage, request.tau);
  return t;
}

}  // namespace penumbra::compare
