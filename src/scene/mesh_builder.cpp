// Procedural primitives.
#include "mesh_builder.h"

#include <cmath>

namespace penumbra::scene {
namespace {

void addQuad(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal) {
  const uint32_t base = uint32_t(mesh.vertices.size());
  for (glm::vec3 p : {a, b, c, d}) mesh.vertices.push_back({p, normal});
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
}

}  // namespace

Mesh makeMesh(glm::vec3 albedo) {
  Mesh mesh;
  mesh.albedo = albedo;
  return mesh;
}

void addOrientedBox(Mesh& mesh, glm::vec3 centre, glm::vec3 halfExtents, const glm::mat3& axes) {
  // Each face: its normal axis and two tangent axes ordered so that the quad winds outward.
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      const glm::vec3 n = axes[axis] * sign;
      const glm::vec3 u = axes[(axis + 1) % 3] * halfExtents[(axis + 1) % 3];
      const glm::vec3 v = axes[(axis + 2) % 3] * halfExtents[(axis + 2) % 3];
      const glm::vec3 c = centre + n * halfExtents[axis];
      if (sign > 0.0f) {
        addQuad(mesh, c - u - v, c + u - v, c + u + v, c - u + v, n);
      } else {
        addQuad(mesh, c - u - v, c - u + v, c + u + v, c + u - v, n);
      }
    }
  }
}

void addBox(Mesh& mesh, glm::vec3 centre, glm::vec3 halfExtents, float yawRadians) {
  const float c = std::cos(yawRadians), s = std::sin(yawRadians);
  const glm::mat3 axes(glm::vec3(c, 0.0f, -s), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(s, 0.0f, c));
  addOrientedBox(mesh, centre, halfExtents, axes);
}

void addGround(Mesh& mesh, glm::vec3 centre, float halfSize) {
  const glm::vec3 x(halfSize, 0.0f, 0.0f), z(0.0f, 0.0f, halfSize);
  addQuad(mesh, centre - x + z, centre + x + z, centre + x - z, centre - x - z,
          glm::vec3(0.0f, 1.0f, 0.0f));
}

void addSphere(Mesh& mesh, glm::vec3 centre, float radius, int segments) {
  const uint32_t base = uint32_t(mesh.vertices.size());
  const int rings = segments / 2;
  for (int r = 0; r <= rings; ++r) {
    const float theta = float(M_PI) * float(r) / float(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * float(M_PI) * float(s) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      mesh.vertices.push_back({centre + radius * n, n});
    }
  }
  const uint32_t stride = uint32_t(segments + 1);
  for (uint32_t r = 0; r < uint32_t(rings); ++r) {
    for (uint32_t s = 0; s < uint32_t(segments); ++s) {
      const uint32_t a = base + r * stride + s, b = a + stride;
      for (uint32_t i : {a, a + 1, b, a + 1, b + 1, b}) mesh.indices.push_back(i);
    }
  }
}

void addCylinder(Mesh& mesh, glm::vec3 baseCentre, float radius, float height, int segments) {
  const uint32_t base = uint32_t(mesh.vertices.size());
  for (int s = 0; s <= segments; ++s) {
    const float phi = 2.0f * float(M_PI) * float(s) / float(segments);
    const glm::vec3 n(std::cos(phi), 0.0f, std::sin(phi));
    mesh.vertices.push_back({baseCentre + radius * n, n});
    mesh.vertices.push_back({baseCentre + radius * n + glm::vec3(0.0f, height, 0.0f), n});
  }
  for (uint32_t s = 0; s < uint32_t(segments); ++s) {
    const uint32_t a = base + 2 * s;
    for (uint32_t i : {a, a + 1, a + 2, a + 1, a + 3, a + 2}) mesh.indices.push_back(i);
  }
  // Caps: a fan around the centre at each end.
  for (float y : {0.0f, height}) {
    const glm::vec3 n(0.0f, y > 0.0f ? 1.0f : -1.0f, 0.0f);
    const uint32_t centre = uint32_t(mesh.vertices.size());
    mesh.vertices.push_back({baseCentre + glm::vec3(0.0f, y, 0.0f), n});
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * float(M_PI) * float(s) / float(segments);
      mesh.vertices.push_back(
          {baseCentre + glm::vec3(radius * std::cos(phi), y, radius * std::sin(phi)), n});
    }
    for (uint32_t s = 0; s < uint32_t(segments); ++s) {
      if (y > 0.0f) {
        for (uint32_t i : {centre, centre + s + 2, centre + s + 1}) mesh.indices.push_back(i);
      } else {
        for (uint32_t i : {centre, centre + s + 1, centre + s + 2}) mesh.indices.push_back(i);
      }
    }
  }
}

}  // namespace penumbra::scene
