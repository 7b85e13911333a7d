// Tracing the true shadow (penumbra/truth/true_shadow.h): camera rays through the supersampled
// ground truth's sub-pixels, shadow rays from their hits to the light's sample points.
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../core/parallel.h"
#include "penumbra/error.h"
#include "penumbra/shared/shading.h"
#include "ray_scene_impl.h"
#include "trace_rays.h"

namespace penumbra::truth {
namespace {

constexpr int kMaxTraceSide = 16384;  // output pixels per side
constexpr int64_t kMaxSubPixels = int64_t(1) << 28;

// The share of light the ray from `origin` along `direction` carries to `reach` (in units of
// direction): 0 where an opaque caster blocks it, else the product of 1 - alpha of the
// translucent casters it passes (ShadowRayContext, filterShadowHit).
float transmittance(RTCScene scene, glm::vec3 origin, glm::vec3 direction, float reach) {
  ShadowRayContext context;
  rtcInitIntersectContext(&context.embree);
  RTCRay ray = embreeRay(origin, direction, 0.0f, reach);
  rtcOccluded1(scene, &context.embree, &ray);
  // Embree sets tfar to -infinity when the ray is blocked.
  return ray.tfar >= 0.0f ? context.transmittance : 0.0f;
}

}  // namespace

void checkTrueShadowLightSamples(int count) {
  checkSquareCount(count, 1, 64, "true-shadow light samples");
}

TrueShadow traceTrueShadow(const RayScene& rayScene, const TrueShadowRequest& request) {
  return *traceTrueShadow(rayScene, request, TraceControl{});
}

std::optional<TrueShadow> traceTrueShadow(const RayScene& rayScene,
                                          const TrueShadowRequest& request,
                                          const TraceControl& control) {
  if (request.width < 1 || request.width > kMaxTraceSide || request.height < 1 ||
      request.height > kMaxTraceSide) {
    throw Error("true-shadow image " + std::to_string(request.width) + "x" +
                std::to_string(request.height) + " is out of range [1, " +
                std::to_string(kMaxTraceSide) + "] per side");
  }
  if (request.supersample < 1 || request.supersample > 8) {
    throw Error("true-shadow supersampling " + std::to_string(request.supersample) +
                " is out of range [1, 8]");
  }
  const int S = request.supersample;
  const int bigWidth = request.width * S, bigHeight = request.height * S;
  if (int64_t(bigWidth) * int64_t(bigHeight) > kMaxSubPixels) {
    throw Error("true-shadow sub-pixels " + std::to_string(int64_t(bigWidth) * bigHeight) +
                " exceed " + std::to_string(kMaxSubPixels));
  }
  checkLightSize(request.light);
  if (request.light.size > 0.0f) checkTrueShadowLightSamples(request.lightSamples);
  const SampledLight light = sampleLight(request.light, request.lightSamples);
  const RayScene::Impl& scene = rayScene.impl();

  const CameraRays camera(request);
  const glm::vec3 toLightDirectional = -glm::normalize(request.light.direction);
  const bool perspectiveLight = request.light.kind != LightKind::Directional;
  const glm::vec3 spotAxis = request.light.kind == LightKind::Spot
                                 ? glm::normalize(request.light.target - request.light.position)
                                 : glm::vec3(0.0f, 0.0f, -1.0f);
  const float spotCosine = std::cos(glm::radians(0.5f * request.light.spotAngleDegrees));

  TrueShadow out;
  out.visibility = Image(request.width, request.height, 1, -1.0f);
  out.color = Image(request.width, request.height, 4, 0.0f);
  out.reachedByLight = Image(request.width, request.height, 1, 1.0f);
  out.subPixelViewDepth = Image(bigWidth, bigHeight, 1, std::numeric_limits<float>::infinity());
  std::atomic<uint64_t> cameraRays{0}, shadowRays{0};
  const auto start = std::chrono::steady_clock::now();
  std::atomic<bool> stopped{false};
  detail::parallelForRows(request.height, [&](int y) {
    if (stopped.load(std::memory_order_relaxed)) return;
    if (control.stopRequested && control.stopRequested()) {
      stopped.store(true, std::memory_order_relaxed);
      return;
    }
    uint64_t rowShadowRays = 0;
    for (int x = 0; x < request.width; ++x) {
      double visibilitySum = 0.0;
      int hits = 0;
      glm::vec3 color(0.0f);
      for (int sy = 0; sy < S; ++sy) {
        for (int sx = 0; sx < S; ++sx) {
          const int bx = x * S + sx, by = y * S + sy;
          const glm::vec3 direction = camera.direction(bx, by);
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          RTCRayHit rayHit =
              embreeRayHit(camera.origin, direction, camera.nearDepth, camera.farDepth);
          rtcIntersect1(scene.scene, &context, &rayHit);
          if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            color += shaders::kSkyColour;
            continue;
          }
          const RayMesh& mesh = scene.meshes[rayHit.hit.geomID];
          const uint32_t primitive = rayHit.hit.primID;
          const float u = rayHit.hit.u, v = rayHit.hit.v;
          const SurfacePoint hit = surfacePoint(mesh, primitive, u, v, direction);
          const auto [a, b, c] = mesh.triangle(primitive);
          const glm::vec3 blend =
              (1.0f - u - v) * mesh.normals[a] + u * mesh.normals[b] + v * mesh.normals[c];
          // Opposite vertex normals can cancel: the triangle's own normal then (never NaN).
          const glm::vec3 smooth =
              glm::dot(blend, blend) > 1e-12f
                  ? glm::normalize(blend)
                  : (hit.frontFacing ? hit.geometricNormal : -hit.geometricNormal);
          const glm::vec3 shadingNormal = hit.frontFacing ? smooth : -smooth;
          out.subPixelViewDepth.at(bx, by) = rayHit.ray.tfar;
          const float visibility =
              lightVisibility(light, hit.position, hit.geometricNormal, gridShift(bx, by),
                              [&](glm::vec3 origin, glm::vec3 towards, float reach) {
                                ++rowShadowRays;
                                return transmittance(scene.scene, origin, towards, reach);
                              });
          visibilitySum += visibility;
          ++hits;
          // Shading as the camera pass's (passes/camera.frag): Lambert with the smooth normal
          // towards the light's centre, the spot cone's edge, the shared formula.
          const glm::vec3 toLight = perspectiveLight
                                        ? glm::normalize(request.light.position - hit.position)
                                        : toLightDirectional;
          float lightAmount = std::max(glm::dot(shadingNormal, toLight), 0.0f);
          float cone = 1.0f;
          if (request.light.kind == LightKind::Spot) {
            cone = shaders::spotConeFalloff(glm::dot(-toLight, spotAxis), spotCosine);
            lightAmount *= cone;
          }
          if (!(glm::dot(hit.geometricNormal, toLight) > shaders::kGrazingCosine) ||
              !(cone > 0.0f)) {
            out.reachedByLight.at(x, y) = 0.0f;
          }
          const glm::vec3 base(mesh.baseColor(primitive, u, v));
          color += shaders::shadeLambert(base, request.ambient, lightAmount, visibility);
        }
      }
      cameraRays.fetch_add(uint64_t(S) * uint64_t(S), std::memory_order_relaxed);
      if (hits > 0) out.visibility.at(x, y) = float(visibilitySum / hits);
      color /= float(S * S);
      for (int ch = 0; ch < 3; ++ch) out.color.at(x, y, ch) = color[ch];
      out.color.at(x, y, 3) = 1.0f;
    }
    shadowRays.fetch_add(rowShadowRays, std::memory_order_relaxed);
    if (control.rowsDone != nullptr) control.rowsDone->fetch_add(1, std::memory_order_release);
  });
  if (stopped.load()) return std::nullopt;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.cameraRays = cameraRays.load();
  out.shadowRays = shadowRays.load();
  return out;
}

SurfaceMatch matchRasterisedSurfaces(const TrueShadow& trace, const Image& rasterWindowDepth,
                                     const TrueShadowRequest& request) {
  const Image& traced = trace.subPixelViewDepth;
  const int S = request.supersample;
  if (rasterWindowDepth.width() != traced.width() ||
      rasterWindowDepth.height() != traced.height() || rasterWindowDepth.channels() != 1 ||
      traced.width() != request.width * S || traced.height() != request.height * S) {
    throw Error("the rasterised depth (" + std::to_string(rasterWindowDepth.width()) + "x" +
                std::to_string(rasterWindowDepth.height()) + ") is not the traced sub-pixels' (" +
                std::to_string(traced.width()) + "x" + std::to_string(traced.height()) + ")");
  }
  // The rasteriser's window depth back to view depth through its own projection (glm's
  // OpenGL convention, clip z in [-w, w]): ndc = -P22 + P32 / depth.
  const float aspect = float(request.width) / float(request.height);
  const glm::mat4 projection = clipFromView(request.camera, aspect, request.viewBounds);
  const double p22 = projection[2][2], p32 = projection[3][2];
  SurfaceMatch match;
  match.matched = Image(request.width, request.height, 1, 1.0f);
  for (int y = 0; y < request.height; ++y) {
    for (int x = 0; x < request.width; ++x) {
      int mismatched = 0;
      for (int sy = 0; sy < S; ++sy) {
        for (int sx = 0; sx < S; ++sx) {
          const float window = rasterWindowDepth.at(x * S + sx, y * S + sy);
          const float depth = traced.at(x * S + sx, y * S + sy);
          const bool rasterMiss = !(window < 1.0f);
          const bool traceMiss = !std::isfinite(depth);
          bool same = rasterMiss && traceMiss;
          if (!rasterMiss && !traceMiss) {
            const double ndc = 2.0 * double(window) - 1.0;
            const double rasterDepth = p32 / (ndc + p22);
            same = std::abs(rasterDepth - double(depth)) <=
                   double(kSurfaceMatchTolerance) * double(depth);
          }
          if (!same) ++mismatched;
        }
      }
      if (mismatched > 0) {
        match.matched.at(x, y) = 0.0f;
        ++match.excludedPixels;
        match.mismatchedSubPixels += mismatched;
      }
    }
  }
  return match;
}

MeasuredPixels measuredPixels(const Image& shadowTestCoverage, const TrueShadow& trace,
                              const SurfaceMatch& match) {
  const int width = trace.visibility.width(), height = trace.visibility.height();
  if (shadowTestCoverage.width() != width || shadowTestCoverage.height() != height ||
      match.matched.width() != width || match.matched.height() != height) {
    throw Error("the frame's coverage, the trace and the surface match differ in size");
  }
  MeasuredPixels m;
  m.coverage = Image(width, height, 1, 0.0f);
  m.exclusion = Image(width, height, 1, 0.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!(shadowTestCoverage.at(x, y) > 0.5f)) continue;
      if (match.matched.at(x, y) < 0.5f || trace.visibility.at(x, y) < 0.0f) {
        m.exclusion.at(x, y) = kExcludedSurface;
        ++m.excludedPixels;
      } else if (trace.reachedByLight.at(x, y) < 0.5f) {
        m.exclusion.at(x, y) = kExcludedUnlit;
        ++m.unlitPixels;
      } else {
        m.coverage.at(x, y) = 1.0f;
      }
    }
  }
  return m;
}

}  // namespace penumbra::truth
