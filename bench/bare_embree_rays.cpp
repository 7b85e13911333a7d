// Recording the true shadow's rays and casting them with nothing but Embree (bare_embree_rays.h).
// The rays come from src/truth/trace_rays.h, the tracer's own: the recorded counts are also
// checked against the trace's.
#include "bare_embree_rays.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <mutex>

#include "../src/core/parallel.h"
#include "../src/truth/ray_scene_impl.h"
#include "../src/truth/trace_rays.h"
#include "penumbra/area_light.h"
#include "penumbra/error.h"

namespace penumbra::bench {
namespace {

RecordedRay makeRay(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) {
  return {origin, direction, tnear, tfar};
}

}  // namespace

RecordedRays recordTrueShadowRays(const truth::RayScene& rayScene,
                                  const truth::TrueShadowRequest& request, int rowStride) {
  const truth::RayScene::Impl& scene = rayScene.impl();
  const int S = request.supersample;
  const truth::CameraRays cameraRays(request);
  const truth::SampledLight light = truth::sampleLight(request.light, request.lightSamples);

  RecordedRays out;
  std::mutex keep;
  std::atomic<uint64_t> cameraRayCount{0}, shadowRays{0};
  detail::parallelForRows(request.height, [&](int y) {
    const bool kept = y % rowStride == 0;
    std::vector<RecordedRay> camera, shadow;
    uint64_t rowShadowRays = 0;
    for (int x = 0; x < request.width; ++x) {
      for (int sy = 0; sy < S; ++sy) {
        for (int sx = 0; sx < S; ++sx) {
          const int bx = x * S + sx, by = y * S + sy;
          const glm::vec3 direction = cameraRays.direction(bx, by);
          const RecordedRay cameraRay =
              makeRay(cameraRays.origin, direction, cameraRays.nearDepth, cameraRays.farDepth);
          if (kept) camera.push_back(cameraRay);
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          RTCRayHit rayHit = truth::embreeRayHit(cameraRays.origin, direction, cameraRays.nearDepth,
                                                 cameraRays.farDepth);
          rtcIntersect1(scene.scene, &context, &rayHit);
          if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
          const truth::SurfacePoint hit =
              truth::surfacePoint(scene.meshes[rayHit.hit.geomID], rayHit.hit.primID, rayHit.hit.u,
                                  rayHit.hit.v, direction);
          truth::lightVisibility(light, hit.position, hit.geometricNormal, truth::gridShift(bx, by),
                                 [&](glm::vec3 origin, glm::vec3 towards, float reach) {
                                   ++rowShadowRays;
                                   if (kept)
                                     shadow.push_back(makeRay(origin, towards, 0.0f, reach));
                                   return true;
                                 });
        }
      }
    }
    cameraRayCount.fetch_add(uint64_t(request.width) * uint64_t(S * S), std::memory_order_relaxed);
    shadowRays.fetch_add(rowShadowRays, std::memory_order_relaxed);
    if (kept) {
      const std::lock_guard<std::mutex> lock(keep);
      out.camera.insert(out.camera.end(), camera.begin(), camera.end());
      out.shadow.insert(out.shadow.end(), shadow.begin(), shadow.end());
    }
  });
  out.cameraRaysInFrame = cameraRayCount.load();
  out.shadowRaysInFrame = shadowRays.load();
  return out;
}

BareTiming castBare(const truth::RayScene& rayScene, const RecordedRays& rays) {
  const RTCScene scene = rayScene.impl().scene;
  constexpr int kChunk = 1024;
  auto chunks = [](size_t n) { return int((n + kChunk - 1) / kChunk); };
  std::atomic<uint64_t> hits{0}, unblocked{0};
  const auto start = std::chrono::steady_clock::now();
  detail::parallelForRows(chunks(rays.camera.size()), [&](int chunk) {
    const size_t end = std::min(rays.camera.size(), size_t(chunk + 1) * kChunk);
    uint64_t chunkHits = 0;
    for (size_t k = size_t(chunk) * kChunk; k < end; ++k) {
      const RecordedRay& r = rays.camera[k];
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRayHit rayHit = truth::embreeRayHit(r.origin, r.direction, r.tnear, r.tfar);
      rtcIntersect1(scene, &context, &rayHit);
      chunkHits += rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    hits.fetch_add(chunkHits, std::memory_order_relaxed);
  });
  detail::parallelForRows(chunks(rays.shadow.size()), [&](int chunk) {
    const size_t end = std::min(rays.shadow.size(), size_t(chunk + 1) * kChunk);
    uint64_t chunkUnblocked = 0;
    for (size_t k = size_t(chunk) * kChunk; k < end; ++k) {
      const RecordedRay& r = rays.shadow[k];
      // The truth's context: a translucent caster's filter keeps its transmittance there.
      truth::ShadowRayContext context;
      rtcInitIntersectContext(&context.embree);
      RTCRay ray = truth::embreeRay(r.origin, r.direction, r.tnear, r.tfar);
      rtcOccluded1(scene, &context.embree, &ray);
      chunkUnblocked += ray.tfar >= 0.0f;
    }
    unblocked.fetch_add(chunkUnblocked, std::memory_order_relaxed);
  });
  BareTiming t;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  t.rays = rays.camera.size() + rays.shadow.size();
  t.cameraHits = hits.load();
  t.shadowUnblocked = unblocked.load();
  return t;
}

}  // namespace penumbra::bench
