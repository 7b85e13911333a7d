// Recording the true shadow's rays and casting them with nothing but Embree (bare_embree_rays.h).
// The ray formulas are src/truth/true_shadow.cpp's, restated: the recorded counts are checked
// against the trace's own, so a drift between the two shows.
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
#include "../src/truth/surface_offset.h"
#include "penumbra/area_light.h"
#include "penumbra/error.h"

namespace penumbra::bench {
namespace {

constexpr float kForever = std::numeric_limits<float>::infinity();

// true_shadow.cpp's gridShift, gridPoint and polarDiskPoint.
glm::vec2 gridShift(int x, int y) {
  uint64_t z = (uint64_t(uint32_t(x)) << 32 | uint32_t(y)) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return glm::vec2(float(z >> 40) * 0x1p-24f, float((z >> 8) & 0xffffffu) * 0x1p-24f);
}

glm::vec2 gridPoint(int i, int j, int side, glm::vec2 shift) {
  const glm::vec2 p((float(i) + 0.5f) / float(side) + shift.x,
                    (float(j) + 0.5f) / float(side) + shift.y);
  return p - glm::floor(p);
}

glm::vec2 polarDiskPoint(glm::vec2 square) {
  const float r = std::sqrt(square.x), phi = 2.0f * glm::pi<float>() * square.y;
  return r * glm::vec2(std::cos(phi), std::sin(phi));
}

RecordedRay makeRay(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) {
  return {{origin.x, origin.y, origin.z}, {direction.x, direction.y, direction.z}, tnear, tfar};
}

}  // namespace

RecordedRays recordTrueShadowRays(const truth::RayScene& rayScene,
                                  const truth::TrueShadowRequest& request, int rowStride) {
  const Light& light = request.light;
  const bool soft = light.size > 0.0f;
  if (soft && light.kind == LightKind::Point) {
    throw Error("recording a sphere light's rays is not implemented (a disk light's only)");
  }
  const truth::RayScene::Impl& scene = rayScene.impl();
  const int S = request.supersample;
  const int bigWidth = request.width * S, bigHeight = request.height * S;
  const float aspect = float(request.width) / float(request.height);
  const glm::mat4 projection = clipFromView(request.camera, aspect, request.sceneBounds);
  const glm::mat3 worldFromView = glm::transpose(glm::mat3(viewFromWorld(request.camera)));
  const float farDepth = cameraFar(request.camera, request.sceneBounds);
  const bool atInfinity = light.kind == LightKind::Directional;
  const int side = soft ? int(std::lround(std::sqrt(double(request.lightSamples)))) : 0;
  const LightDisk disk = soft ? lightDisk(light) : LightDisk{};
  const glm::vec3 hardTowards = atInfinity ? -glm::normalize(light.direction) : light.position;

  RecordedRays out;
  std::mutex keep;
  std::atomic<uint64_t> cameraRays{0}, shadowRays{0};
  detail::parallelForRows(request.height, [&](int y) {
    const bool kept = y % rowStride == 0;
    std::vector<RecordedRay> camera, shadow;
    uint64_t rowShadowRays = 0;
    auto addShadowRay = [&](glm::vec3 origin, glm::vec3 normal, glm::vec3 direction, float reach) {
      if (!(glm::dot(direction, normal) > 0.0f)) return;
      ++rowShadowRays;
      if (kept) shadow.push_back(makeRay(origin, direction, 0.0f, reach));
    };
    for (int x = 0; x < request.width; ++x) {
      for (int sy = 0; sy < S; ++sy) {
        for (int sx = 0; sx < S; ++sx) {
          const int bx = x * S + sx, by = y * S + sy;
          const float ndcX = (float(bx) + 0.5f) / float(bigWidth) * 2.0f - 1.0f;
          const float ndcY = 1.0f - (float(by) + 0.5f) / float(bigHeight) * 2.0f;
          const glm::vec3 direction =
              worldFromView * glm::vec3(ndcX / projection[0][0], ndcY / projection[1][1], -1.0f);
          const RecordedRay cameraRay =
              makeRay(request.camera.position, direction, kCameraNear, farDepth);
          if (kept) camera.push_back(cameraRay);
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          RTCRayHit rayHit{};
          rayHit.ray.org_x = cameraRay.origin[0];
          rayHit.ray.org_y = cameraRay.origin[1];
          rayHit.ray.org_z = cameraRay.origin[2];
          rayHit.ray.dir_x = direction.x;
          rayHit.ray.dir_y = direction.y;
          rayHit.ray.dir_z = direction.z;
          rayHit.ray.tnear = cameraRay.tnear;
          rayHit.ray.tfar = cameraRay.tfar;
          rayHit.ray.mask = ~0u;
          rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(scene.scene, &context, &rayHit);
          if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
          const truth::RayMesh& mesh = scene.meshes[rayHit.hit.geomID];
          const float u = rayHit.hit.u, v = rayHit.hit.v;
          const auto [a, b, c] = mesh.triangle(rayHit.hit.primID);
          const glm::vec3 position =
              (1.0f - u - v) * mesh.positions[a] + u * mesh.positions[b] + v * mesh.positions[c];
          const glm::vec3 front = glm::cross(mesh.positions[b] - mesh.positions[a],
                                             mesh.positions[c] - mesh.positions[a]);
          const glm::vec3 normal =
              glm::normalize(glm::dot(front, direction) < 0.0f ? front : -front);
          const glm::vec3 origin = truth::offsetRayOrigin(position, normal);
          if (!soft) {
            addShadowRay(origin, normal, atInfinity ? hardTowards : hardTowards - origin,
                         atInfinity ? kForever : 1.0f);
            continue;
          }
          const glm::vec2 shift = gridShift(bx, by);
          for (int j = 0; j < side; ++j) {
            for (int i = 0; i < side; ++i) {
              const glm::vec2 p = polarDiskPoint(gridPoint(i, j, side, shift));
              const glm::vec3 point = disk.centre + p.x * disk.axisA + p.y * disk.axisB;
              addShadowRay(origin, normal, atInfinity ? point : point - origin,
                           atInfinity ? kForever : 1.0f);
            }
          }
        }
      }
    }
    cameraRays.fetch_add(uint64_t(request.width) * uint64_t(S * S), std::memory_order_relaxed);
    shadowRays.fetch_add(rowShadowRays, std::memory_order_relaxed);
    if (kept) {
      const std::lock_guard<std::mutex> lock(keep);
      out.camera.insert(out.camera.end(), camera.begin(), camera.end());
      out.shadow.insert(out.shadow.end(), shadow.begin(), shadow.end());
    }
  });
  out.cameraRaysInFrame = cameraRays.load();
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
      RTCRayHit rayHit{};
      rayHit.ray.org_x = r.origin[0];
      rayHit.ray.org_y = r.origin[1];
      rayHit.ray.org_z = r.origin[2];
      rayHit.ray.dir_x = r.direction[0];
      rayHit.ray.dir_y = r.direction[1];
      rayHit.ray.dir_z = r.direction[2];
      rayHit.ray.tnear = r.tnear;
      rayHit.ray.tfar = r.tfar;
      rayHit.ray.mask = ~0u;
      rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
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
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRay ray{};
      ray.org_x = r.origin[0];
      ray.org_y = r.origin[1];
      ray.org_z = r.origin[2];
      ray.dir_x = r.direction[0];
      ray.dir_y = r.direction[1];
      ray.dir_z = r.direction[2];
      ray.tnear = r.tnear;
      ray.tfar = r.tfar;
      ray.mask = ~0u;
      rtcOccluded1(scene, &context, &ray);
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
