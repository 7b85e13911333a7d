// Tracing the true shadow (penumbra/truth/true_shadow.h): camera rays through the supersampled
// ground truth's sub-pixels, shadow rays from their hits to the light's sample points.
#include <atomic>
#include <chrono>
#include <glm/gtc/constants.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../core/parallel.h"
#include "penumbra/area_light.h"
#include "penumbra/error.h"
#include "ray_scene_impl.h"
#include "shared/shading.h"
#include "surface_offset.h"

namespace penumbra::truth {
namespace {

constexpr glm::vec3 kSky{0.62f, 0.72f, 0.86f};  // the camera pass's clear colour
constexpr int kMaxTraceSide = 16384;             // output pixels per side
constexpr int64_t kMaxSubPixels = int64_t(1) << 28;

// The light as the shadow rays see it: one point (or direction) for a hard light; for a disk or
// a sphere, a side x side grid of cells over the unit square, each 1/N of the light — mapped onto
// the disk (each point 1/N of its area, the area-light reference's weights), or onto the cone of
// directions under which each receiver sees the sphere (1/N of its solid angle): lightVisibility.
// Each sub-pixel shifts the grid its own way (gridShift).
struct SampledLight {
  Light light;
  bool atInfinity = false;  // directional
  int side = 0;             // 0: a hard light
  glm::vec3 hardTowards{0.0f};  // hard: the direction to the light (directional) or its position
  LightDisk disk{};             // a disk light's frame
};

SampledLight sampleLight(const Light& light, int samples) {
  SampledLight s;
  s.light = light;
  s.atInfinity = light.kind == LightKind::Directional;
  if (!(light.size > 0.0f)) {
    s.hardTowards = s.atInfinity ? -glm::normalize(light.direction) : light.position;
    return s;
  }
  s.side = int(std::lround(std::sqrt(double(samples))));
  if (light.kind != LightKind::Point) s.disk = lightDisk(light);
  return s;
}

// Sub-pixel (x, y)'s toroidal shift of the sample grid over the unit square (Cranley and
// Patterson, "Randomization of Number Theoretic Methods for Multiple Integration", 1976): every
// cell still holds one point, and the sub-pixels' errors, which a fixed grid repeats along an
// edge, become independent and average out over the pixel. Two fixed pseudo-random numbers in
// [0, 1) from the splitmix64 hash of the position, so a trace is the same on every run.
glm::vec2 gridShift(int x, int y) {
  uint64_t z = (uint64_t(uint32_t(x)) << 32 | uint32_t(y)) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return glm::vec2(float(z >> 40) * 0x1p-24f, float((z >> 8) & 0xffffffu) * 0x1p-24f);
}

// One axis of a side x side grid over the unit square: each cell's centre, shifted and wrapped.
// A grid point is (u_i, v_j), so the maps below take their trigonometry per row and column, not
// per point.
void gridAxis(int side, float shift, std::vector<float>& out) {
  out.resize(size_t(side));
  for (int k = 0; k < side; ++k) {
    const float p = (float(k) + 0.5f) / float(side) + shift;
    out[size_t(k)] = p - std::floor(p);
  }
}

// Unit vectors cos(2 pi v) a + sin(2 pi v) b for each v: the azimuths of the polar maps below.
void spokes(const std::vector<float>& v, glm::vec3 a, glm::vec3 b, std::vector<glm::vec3>& out) {
  out.resize(v.size());
  for (size_t k = 0; k < v.size(); ++k) {
    const float phi = 2.0f * glm::pi<float>() * v[k];
    out[k] = std::cos(phi) * a + std::sin(phi) * b;
  }
}

struct Hit {
  glm::vec3 position;
  glm::vec3 geometricNormal;  // unit, on the side the camera sees
  glm::vec3 shadingNormal;    // unit, flipped like the camera pass's for back faces
  glm::vec3 baseColor;
  float viewDepth = 0.0f;
};

// Whether the ray from `origin` along `direction` reaches `reach` (in units of direction)
// unblocked.
bool unblocked(RTCScene scene, glm::vec3 origin, glm::vec3 direction, float reach) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = direction.x;
  ray.dir_y = direction.y;
  ray.dir_z = direction.z;
  ray.tnear = 0.0f;
  ray.tfar = reach;
  ray.mask = ~0u;
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar >= 0.0f;  // Embree sets tfar to -infinity when the ray is blocked
}

// The share of the light the surface at `hit` sees from the camera's side. A light sample
// behind that side is blocked by the surface itself (a thin surface's far side is another
// surface); the others by an occlusion ray from the offset origin.
float lightVisibility(RTCScene scene, const SampledLight& light, const Hit& hit, glm::vec2 shift,
                      uint64_t& shadowRays) {
  const glm::vec3 origin = offsetRayOrigin(hit.position, hit.geometricNormal);
  auto seen = [&](glm::vec3 direction, float reach) {
    if (!(glm::dot(direction, hit.geometricNormal) > 0.0f)) return 0;
    ++shadowRays;
    return unblocked(scene, origin, direction, reach) ? 1 : 0;
  };
  constexpr float kForever = std::numeric_limits<float>::infinity();
  if (light.side == 0) {
    // A point is reached at t = 1 (nothing lies beyond it on the way); a direction never.
    return float(light.atInfinity ? seen(light.hardTowards, kForever)
                                  : seen(light.hardTowards - origin, 1.0f));
  }
  thread_local std::vector<float> u, v;
  thread_local std::vector<glm::vec3> azimuths;
  gridAxis(light.side, shift.x, u);
  gridAxis(light.side, shift.y, v);
  int count = 0;
  if (light.light.kind == LightKind::Point) {
    // The cone of directions from the receiver towards the sphere of radius r at distance d, half
    // angle alpha = asin(r / d), sampled by Archimedes' map cos(theta) = 1 - u (1 - cos(alpha)),
    // phi = 2 pi v, which keeps area, so the grid's points are uniform in solid angle over the
    // cone (docs/reference.md, Sphere lights); each ray must reach the sphere's near surface,
    // d cos(theta) - sqrt(r^2 - d^2 sin^2(theta)).
    const glm::vec3 toCentre = light.light.position - hit.position;
    const double distance = glm::length(toCentre);
    const double radius = 0.5 * double(light.light.size);
    if (!(distance > radius)) return 1.0f;  // inside the light: it is all around
    const glm::vec3 axis = toCentre / float(distance);
    const glm::vec3 helper =
        std::abs(axis.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 a = glm::normalize(glm::cross(axis, helper));
    spokes(v, a, glm::cross(axis, a), azimuths);
    const double cosAlpha =
        std::sqrt(std::max(0.0, 1.0 - (radius * radius) / (distance * distance)));
    for (int i = 0; i < light.side; ++i) {
      const double cosTheta = 1.0 - double(u[size_t(i)]) * (1.0 - cosAlpha);
      const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
      const double across = distance * sinTheta;
      const float reach = float(distance * cosTheta -
                                std::sqrt(std::max(0.0, radius * radius - across * across)));
      for (const glm::vec3& azimuth : azimuths) {
        count += seen(float(sinTheta) * azimuth + float(cosTheta) * axis, reach);
      }
    }
  } else {
    // The disk by the polar map r = sqrt(u), phi = 2 pi v, which keeps area, so each point stands
    // for 1/N of the disk, as the area-light reference's concentric map's do. Not the concentric
    // map: a straight edge seen through a shifted grid under it left 2.4x the error
    // (docs/reference.md, Ray-traced truth), since it runs along that map's rows in places,
    // every cell along it off the same way.
    spokes(v, light.disk.axisA, light.disk.axisB, azimuths);
    for (int i = 0; i < light.side; ++i) {
      const float r = std::sqrt(u[size_t(i)]);
      for (const glm::vec3& azimuth : azimuths) {
        const glm::vec3 point = light.disk.centre + r * azimuth;
        count += light.atInfinity ? seen(point, kForever) : seen(point - origin, 1.0f);
      }
    }
  }
  return float(count) / float(light.side * light.side);
}

}  // namespace

void checkTrueShadowLightSamples(int count) {
  const int side = int(std::lround(std::sqrt(double(std::max(count, 0)))));
  if (count < 1 || count > kMaxTrueShadowLightSamples || side * side != count) {
    throw Error("true-shadow light samples " + std::to_string(count) +
                " must be a square side^2 with side in [1, 64] (1, 4, 9, ..., 4096)");
  }
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

  // Camera rays in view space through each sub-pixel's centre on the image plane at view depth
  // 1, so a hit's ray parameter is its view depth and the near and far planes bound it exactly
  // as they clip the rasteriser.
  const float aspect = float(request.width) / float(request.height);
  const glm::mat4 projection = clipFromView(request.camera, aspect, request.sceneBounds);
  const glm::mat3 worldFromView = glm::transpose(glm::mat3(viewFromWorld(request.camera)));
  const float nearDepth = kCameraNear;
  const float farDepth = cameraFar(request.camera, request.sceneBounds);
  const glm::vec3 toLightDirectional = -glm::normalize(request.light.direction);
  const bool perspectiveLight = request.light.kind != LightKind::Directional;
  const glm::vec3 spotAxis = request.light.kind == LightKind::Spot
                                 ? glm::normalize(request.light.target - request.light.position)
                                 : glm::vec3(0.0f, 0.0f, -1.0f);
  const float spotCosine = std::cos(glm::radians(0.5f * request.light.spotAngleDegrees));

  TrueShadow out;
  out.visibility = Image(request.width, request.height, 1, -1.0f);
  out.color = Image(request.width, request.height, 4, 0.0f);
  out.facesLight = Image(request.width, request.height, 1, 1.0f);
  out.subPixelViewDepth =
      Image(bigWidth, bigHeight, 1, std::numeric_limits<float>::infinity());
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
          const float ndcX = (float(bx) + 0.5f) / float(bigWidth) * 2.0f - 1.0f;
          const float ndcY = 1.0f - (float(by) + 0.5f) / float(bigHeight) * 2.0f;
          const glm::vec3 direction =
              worldFromView * glm::vec3(ndcX / projection[0][0], ndcY / projection[1][1], -1.0f);
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          RTCRayHit rayHit{};
          rayHit.ray.org_x = request.camera.position.x;
          rayHit.ray.org_y = request.camera.position.y;
          rayHit.ray.org_z = request.camera.position.z;
          rayHit.ray.dir_x = direction.x;
          rayHit.ray.dir_y = direction.y;
          rayHit.ray.dir_z = direction.z;
          rayHit.ray.tnear = nearDepth;
          rayHit.ray.tfar = farDepth;
          rayHit.ray.mask = ~0u;
          rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(scene.scene, &context, &rayHit);
          if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            color += kSky;
            continue;
          }
          const RayMesh& mesh = scene.meshes[rayHit.hit.geomID];
          const uint32_t primitive = rayHit.hit.primID;
          const float u = rayHit.hit.u, v = rayHit.hit.v;
          const auto [a, b, c] = mesh.triangle(primitive);
          Hit hit;
          hit.position = (1.0f - u - v) * mesh.positions[a] + u * mesh.positions[b] +
                         v * mesh.positions[c];
          const glm::vec3 front = glm::cross(mesh.positions[b] - mesh.positions[a],
                                             mesh.positions[c] - mesh.positions[a]);
          const bool frontFacing = glm::dot(front, direction) < 0.0f;
          hit.geometricNormal = glm::normalize(frontFacing ? front : -front);
          const glm::vec3 shading = glm::normalize((1.0f - u - v) * mesh.normals[a] +
                                                   u * mesh.normals[b] + v * mesh.normals[c]);
          hit.shadingNormal = frontFacing ? shading : -shading;
          hit.viewDepth = rayHit.ray.tfar;
          out.subPixelViewDepth.at(bx, by) = hit.viewDepth;
          const float visibility =
              lightVisibility(scene.scene, light, hit, gridShift(bx, by), rowShadowRays);
          visibilitySum += visibility;
          ++hits;
          // Shading as the camera pass's (passes/camera.frag): Lambert with the smooth normal
          // towards the light's centre, the spot cone's edge, the shared formula.
          const glm::vec3 toLight = perspectiveLight
                                        ? glm::normalize(request.light.position - hit.position)
                                        : toLightDirectional;
          if (!(glm::dot(hit.geometricNormal, toLight) > shaders::kGrazingCosine)) {
            out.facesLight.at(x, y) = 0.0f;
          }
          float lightAmount = std::max(glm::dot(hit.shadingNormal, toLight), 0.0f);
          if (request.light.kind == LightKind::Spot) {
            lightAmount *= shaders::spotConeFalloff(glm::dot(-toLight, spotAxis), spotCosine);
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
  const glm::mat4 projection = clipFromView(request.camera, aspect, request.sceneBounds);
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

}  // namespace penumbra::truth
