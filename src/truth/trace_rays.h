// The rays of the true shadow (penumbra/truth/true_shadow.h), shared by the tracer and the
// benchmark's bare Embree loop so that both cast the same rays: the camera's ray through each
// sub-pixel, the surface point it hits, and the light's sample rays from there.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <vector>

#include "penumbra/area_light.h"
#include "penumbra/scene.h"
#include "penumbra/truth/true_shadow.h"
#include "ray_scene_impl.h"
#include "surface_offset.h"

namespace penumbra::truth {

// An Embree ray from `origin` along `direction` over [tnear, tfar] (in units of direction), and
// the same as a ray-hit record with no hit yet.
inline RTCRay embreeRay(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) {
  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = direction.x;
  ray.dir_y = direction.y;
  ray.dir_z = direction.z;
  ray.tnear = tnear;
  ray.tfar = tfar;
  ray.mask = ~0u;
  return ray;
}
inline RTCRayHit embreeRayHit(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) {
  RTCRayHit rayHit{};
  rayHit.ray = embreeRay(origin, direction, tnear, tfar);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  return rayHit;
}

// Camera rays in view space through each sub-pixel's centre on the image plane at view depth 1,
// so a hit's ray parameter is its view depth and the near and far planes bound it exactly as
// they clip the rasteriser.
struct CameraRays {
  glm::vec3 origin;
  glm::mat3 worldFromView;
  float xScale, yScale;  // 1 / projection[0][0], 1 / projection[1][1]
  int subPixelsWide, subPixelsHigh;
  float nearDepth, farDepth;

  explicit CameraRays(const TrueShadowRequest& request)
      : origin(request.camera.position),
        worldFromView(glm::transpose(glm::mat3(viewFromWorld(request.camera)))),
        subPixelsWide(request.width * request.supersample),
        subPixelsHigh(request.height * request.supersample),
        nearDepth(cameraNear(request.viewBounds)),
        farDepth(cameraFar(request.camera, request.viewBounds)) {
    const glm::mat4 projection = clipFromView(
        request.camera, float(request.width) / float(request.height), request.viewBounds);
    xScale = 1.0f / projection[0][0];
    yScale = 1.0f / projection[1][1];
  }

  // Sub-pixel (x, y), row 0 at the top, of the supersampled frame.
  glm::vec3 direction(int x, int y) const {
    const float ndcX = (float(x) + 0.5f) / float(subPixelsWide) * 2.0f - 1.0f;
    const float ndcY = 1.0f - (float(y) + 0.5f) / float(subPixelsHigh) * 2.0f;
    return worldFromView * glm::vec3(ndcX * xScale, ndcY * yScale, -1.0f);
  }
};

// Where a camera ray along `direction` met triangle `primitive` at Embree's barycentrics (u, v):
// the point interpolated from the vertices, and the triangle's unit normal on the camera's side.
struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 geometricNormal;
  bool frontFacing;  // counter-clockwise towards the camera, as the rasteriser decides
};

inline SurfacePoint surfacePoint(const RayMesh& mesh, uint32_t primitive, float u, float v,
                                 glm::vec3 direction) {
  const auto [a, b, c] = mesh.triangle(primitive);
  SurfacePoint p;
  p.position = (1.0f - u - v) * mesh.positions[a] + u * mesh.positions[b] + v * mesh.positions[c];
  const glm::vec3 front = mesh.frontNormal(primitive);
  p.frontFacing = glm::dot(front, direction) < 0.0f;
  p.geometricNormal = glm::normalize(p.frontFacing ? front : -front);
  return p;
}

// The light as the shadow rays see it: one point (or direction) for a hard light; for a disk or
// a sphere, a side x side grid of cells over the unit square, each 1/N of the light — mapped onto
// the disk (each point 1/N of its area, the area-light reference's weights), or onto the cone of
// directions under which each receiver sees the sphere (1/N of its solid angle): lightVisibility.
// Each sub-pixel shifts the grid its own way (gridShift).
struct SampledLight {
  Light light;
  bool atInfinity = false;      // directional
  int side = 0;                 // 0: a hard light
  glm::vec3 hardTowards{0.0f};  // hard: the direction to the light (directional) or its position
  LightDisk disk{};             // a disk light's frame
};

inline SampledLight sampleLight(const Light& light, int samples) {
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
inline glm::vec2 gridShift(int x, int y) {
  uint64_t z = (uint64_t(uint32_t(x)) << 32 | uint32_t(y)) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return glm::vec2(float(z >> 40) * 0x1p-24f, float((z >> 8) & 0xffffffu) * 0x1p-24f);
}

// One axis of a side x side grid over the unit square: each cell's centre, shifted and wrapped.
// A grid point is (u_i, v_j), so the maps below take their trigonometry per row and column, not
// per point.
inline void gridAxis(int side, float shift, std::vector<float>& out) {
  out.resize(size_t(side));
  for (int k = 0; k < side; ++k) {
    const float p = (float(k) + 0.5f) / float(side) + shift;
    out[size_t(k)] = p - std::floor(p);
  }
}

// Unit vectors cos(2 pi v) a + sin(2 pi v) b for each v: the azimuths of the polar maps below.
inline void spokes(const std::vector<float>& v, glm::vec3 a, glm::vec3 b,
                   std::vector<glm::vec3>& out) {
  out.resize(v.size());
  for (size_t k = 0; k < v.size(); ++k) {
    const float phi = 2.0f * glm::pi<float>() * v[k];
    out[k] = std::cos(phi) * a + std::sin(phi) * b;
  }
}

// The share of the light a surface point sees from the side its unit geometric normal points
// to (the camera's): each of the light's samples is a ray from the point moved off its triangle
// (offsetRayOrigin) whose share of light `unblocked(origin, direction, reach)` gives (a bool,
// or the transmittance in [0, 1] through translucent casters) — reach in units of direction. A
// sample behind that side is blocked by the surface itself (a thin surface's far side is another
// surface) and takes no ray. The tracer and the benchmark's bare Embree loop
// (bench/bare_embree_rays.cpp) both cast these rays.
template <typename Unblocked>
float lightVisibility(const SampledLight& light, glm::vec3 position, glm::vec3 normal,
                      glm::vec2 shift, Unblocked&& unblocked) {
  const glm::vec3 origin = offsetRayOrigin(position, normal);
  auto seen = [&](glm::vec3 direction, float reach) {
    if (!(glm::dot(direction, normal) > 0.0f)) return 0.0f;
    return float(unblocked(origin, direction, reach));
  };
  constexpr float kForever = std::numeric_limits<float>::infinity();
  if (light.side == 0) {
    // A point is reached at t = 1 (nothing lies beyond it on the way); a direction never.
    return light.atInfinity ? seen(light.hardTowards, kForever)
                            : seen(light.hardTowards - origin, 1.0f);
  }
  thread_local std::vector<float> u, v;
  thread_local std::vector<glm::vec3> azimuths;
  gridAxis(light.side, shift.x, u);
  gridAxis(light.side, shift.y, v);
  float count = 0.0f;
  if (light.light.kind == LightKind::Point) {
    // The cone of directions from the receiver towards the sphere of radius r at distance d, half
    // angle alpha = asin(r / d), sampled by Archimedes' map cos(theta) = 1 - u (1 - cos(alpha)),
    // phi = 2 pi v, which keeps area, so the grid's points are uniform in solid angle over the
    // cone (docs/reference.md, Sphere lights); each ray must reach the sphere's near surface,
    // d cos(theta) - sqrt(r^2 - d^2 sin^2(theta)).
    const glm::vec3 toCentre = light.light.position - position;
    const double distance = glm::length(toCentre);
    const double radius = 0.5 * double(light.light.size);
    if (!(distance > radius)) return 1.0f;  // inside the light: it is all around
    const glm::vec3 axis = toCentre / float(distance);
    glm::vec3 a, b;
    perpendicularBasis(axis, a, b);
    spokes(v, a, b, azimuths);
    const double cosAlpha =
        std::sqrt(std::max(0.0, 1.0 - (radius * radius) / (distance * distance)));
    for (int i = 0; i < light.side; ++i) {
      const double cosTheta = 1.0 - double(u[size_t(i)]) * (1.0 - cosAlpha);
      const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
      const double across = distance * sinTheta;
      const float reach =
          float(distance * cosTheta - std::sqrt(std::max(0.0, radius * radius - across * across)));
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
  return count / float(light.side * light.side);
}

}  // namespace penumbra::truth
