// The ray-traced truth of a comparison's frame 0 and the shadow-map references measured against
// it (comparison.h TruthResult, docs/reference.md "Ray-traced truth").
#pragma once

#include <functional>

#include "penumbra/compare/comparison.h"

namespace penumbra::compare {

// Frame 0 as rasterised for the references: its lit-surface coverage (litSurfaceMask), the
// depth buffer of the supersampled ground truth's camera pass (Renderer::readCameraDepth), and
// the two references' visibility.
struct RasterisedFrame {
  const Image& coverage;
  const Image& supersampledDepth;
  const Image& referenceVisibility;
  const Image& groundTruthVisibility;
};

// onRows(done, of): output rows traced so far, called from the tracing threads one at a time.
TruthResult measureTruth(const truth::RayScene& rays, const ComparisonRequest& request,
                         const Scene& scene, const Camera& camera, const RasterisedFrame& frame,
                         const std::function<void(int done, int of)>& onRows = {});

}  // namespace penumbra::compare
