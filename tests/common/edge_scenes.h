// Scenes with closed-form soft shadows, shared by the area-light reference's GPU tests and the
// ray-traced truth's tests: a plate with a straight edge over the ground under a sun disk
// straight above, or under a sphere light straight above the edge, and their exact penumbrae.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "penumbra/scene.h"

namespace penumbra {

// A horizontal quad facing +y over [x0, x1] x [z0, z1] at height y.
inline void addQuad(Mesh& mesh, float x0, float x1, float z0, float z1, float y) {
  const uint32_t base = uint32_t(mesh.vertices.size());
  for (glm::vec2 c : {glm::vec2(x0, z0), glm::vec2(x1, z0), glm::vec2(x1, z1), glm::vec2(x0, z1)}) {
    mesh.vertices.push_back({glm::vec3(c.x, y, c.y), glm::vec3(0.0f, 1.0f, 0.0f)});
  }
  for (uint32_t i : {0u, 2u, 1u, 0u, 3u, 2u}) mesh.indices.push_back(base + i);
}

constexpr float kPlateHeight = 1.0f;
constexpr float kSunSize = 0.5f;  // tangent of the angular diameter

// The ground and, at kPlateHeight, a plate over x < 0 whose straight edge runs along z; the sun
// straight above, seen from under the plate's height so the ground beneath it shows.
inline Scene edgeScene() {
  Scene s;
  s.name = "edge";
  Mesh ground;
  addQuad(ground, -2.5f, 2.5f, -2.5f, 2.5f, 0.0f);
  Mesh plate;
  addQuad(plate, -2.5f, 0.0f, -2.0f, 2.0f, kPlateHeight);
  s.meshes = {ground, plate};
  s.camera = {glm::vec3(0.0f, 0.6f, 2.4f), glm::vec3(0.0f, 0.0f, 0.0f), 45.0f};
  s.light.kind = LightKind::Directional;
  s.light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  s.light.size = kSunSize;
  return s;
}

// The share of the unit disk below the chord at height t in [-1, 1]: (pi - acos t + t sqrt(1 -
// t^2)) / pi. A ground point x from the edge's foot sees the sun's disk through the edge shifted
// by h (size / 2) per unit of disk radius, so it is lit by the part of the disk below
// t = x / (h size / 2).
inline double analyticDiskEdgeVisibility(double x) {
  const double t = std::clamp(x / (double(kPlateHeight) * 0.5 * double(kSunSize)), -1.0, 1.0);
  return (glm::pi<double>() - std::acos(t) + t * std::sqrt(1.0 - t * t)) / glm::pi<double>();
}

// A sphere light over the same plate: centre kSphereHeight above the ground, straight above the
// edge, diameter kSphereSize (its bottom at 1.75, above the plate).
constexpr float kSphereHeight = 2.0f;
constexpr float kSphereSize = 0.5f;

inline Scene sphereEdgeScene() {
  Scene s = edgeScene();
  s.light = Light{};
  s.light.kind = LightKind::Point;
  s.light.position = glm::vec3(0.0f, kSphereHeight, 0.0f);
  s.light.size = kSphereSize;
  return s;
}

// The sphere light's visibility at a ground point: the share, by solid angle, of the cone of
// directions towards the sphere that the plate leaves open (the reference's weights make its
// samples stand for solid angle, docs/reference.md). The plate at height h over x < 0 blocks
// the directions w from p = (x, 0, z) with m . w > 0, m = (-h, -x, 0) (normal to the plane
// through p and the edge, which runs from p along (-x, h, 0) and along z). In the cone's frame
// (axis a, half angle asin(r / |c - p|), m at angle beta off the plane perpendicular to a),
// direction (theta, phi) is blocked when cos(theta) sin(beta) + sin(theta) cos(beta) cos(phi) > 0:
// for each theta an arc of phi in closed form, and theta integrated by the midpoint rule (20000
// steps: error below 1e-8; fewer steps where many points are needed, below).
// steps: the midpoint rule's (its error falls as steps^-2: below 1e-6 at 2000).
inline double analyticSphereEdgeVisibility(glm::vec3 ground, int steps = 20000) {
  const glm::dvec3 p(ground);
  const glm::dvec3 c(0.0, double(kSphereHeight), 0.0);
  const double distance = glm::length(c - p);
  const glm::dvec3 a = (c - p) / distance;
  const double alpha = std::asin(0.5 * double(kSphereSize) / distance);
  const glm::dvec3 m = glm::normalize(glm::dvec3(-double(kPlateHeight), -p.x, 0.0));
  const double sinBeta = glm::dot(a, m);
  const double cosBeta = glm::length(m - sinBeta * a);
  double blocked = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double theta = alpha * (double(k) + 0.5) / double(steps);
    const double across = std::sin(theta) * cosBeta;
    double arc = 0.0;
    if (across < 1e-300) {
      arc = std::cos(theta) * sinBeta > 0.0 ? 2.0 * glm::pi<double>() : 0.0;
    } else {
      const double threshold = -std::cos(theta) * sinBeta / across;
      arc = threshold <= -1.0  ? 2.0 * glm::pi<double>()
            : threshold >= 1.0 ? 0.0
                               : 2.0 * std::acos(threshold);
    }
    blocked += std::sin(theta) * arc;
  }
  blocked *= alpha / double(steps);
  return 1.0 - blocked / (2.0 * glm::pi<double>() * (1.0 - std::cos(alpha)));
}

}  // namespace penumbra
