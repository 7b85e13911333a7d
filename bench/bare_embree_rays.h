// Embree's own speed on the true shadow's rays: the camera rays and shadow rays a trace
// (penumbra/truth/true_shadow.h) casts, generated once into arrays by the tracer's own code (src/truth/trace_rays.h), then
// cast alone by a bare loop of rtcIntersect1 / rtcOccluded1 on every core — nothing else in the
// loop, so a trace's rays per second over this loop's is the tracer's overhead.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "penumbra/truth/true_shadow.h"

namespace penumbra::bench {

struct RecordedRay {
  glm::vec3 origin;
  glm::vec3 direction;
  float tnear;
  float tfar;
};

struct RecordedRays {
  std::vector<RecordedRay> camera;  // the kept rows' camera rays
  std::vector<RecordedRay> shadow;  // the kept rows' shadow rays
  // Over the whole frame, kept or not: must equal the trace's own counts (the same rays).
  uint64_t cameraRaysInFrame = 0;
  uint64_t shadowRaysInFrame = 0;
};

// The rays traceTrueShadow casts for `request`, recomputed outside it (camera hits traced here
// untimed). Only output rows y with y % rowStride == 0 are kept, so that 64 samples per sub-pixel
// fit in memory; the counts cover every row.
RecordedRays recordTrueShadowRays(const truth::RayScene& scene,
                                  const truth::TrueShadowRequest& request, int rowStride);

struct BareTiming {
  double seconds = 0.0;  // wall time of both loops
  uint64_t rays = 0;     // camera + shadow rays cast
  uint64_t cameraHits = 0;
  uint64_t shadowUnblocked = 0;
};

// rtcIntersect1 over `rays.camera`, then rtcOccluded1 over `rays.shadow`, each split into
// chunks over the machine's cores (the tracer's row split).
BareTiming castBare(const truth::RayScene& scene, const RecordedRays& rays);

}  // namespace penumbra::bench
