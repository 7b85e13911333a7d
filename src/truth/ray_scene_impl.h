// What a RayScene holds (penumbra/truth/true_shadow.h): the Embree device and BVH, and per mesh
// the copies of geometry and material that the filter functions and the shading read.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "penumbra/scene.h"
#include "penumbra/truth/true_shadow.h"

namespace penumbra::truth {

// A base-colour texture at full resolution (level 0): sRGB colour decoded to linear, alpha
// linear, bilinear between texel centres, repeating as GpuScene's sampler does. The passes
// sample it trilinearly at the mip level of their own footprint, so alpha-tested edges can
// differ by the footprint's blur; where that makes a sub-pixel see another surface, compare
// leaves the pixel out (docs/reference.md, Ray-traced truth).
struct RayTexture {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // linear RGB, linear alpha; row 0 is texcoord v = 0

  glm::vec4 sample(glm::vec2 texcoord) const;
};

struct RayMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> texcoords;
  std::vector<uint32_t> indices;
  glm::vec3 albedo{0.8f};
  float opacity = 1.0f;
  const RayTexture* texture = nullptr;  // into RayScene::Impl::textures
  float alphaCutoff = -1.0f;            // < 0: opaque (shared/alpha_mask.h)
  bool doubleSided = true;
  bool castsShadow = true;   // false: shadow rays pass through it (Mesh::castsShadow)
  bool translucent = false;  // BLEND: shadow rays pass through it, keeping 1 - alpha

  std::array<uint32_t, 3> triangle(uint32_t primitive) const {
    return {indices[3 * primitive], indices[3 * primitive + 1], indices[3 * primitive + 2]};
  }
  // The triangle's normal by its winding (counter-clockwise is the front, as GL's default
  // glFrontFace), not normalised: a camera looking against it sees the front.
  glm::vec3 frontNormal(uint32_t primitive) const {
    const auto [a, b, c] = triangle(primitive);
    return glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
  }
  // The base colour (factor x texture) at barycentric (u, v) of the triangle: Embree's
  // convention, the point (1 - u - v) p0 + u p1 + v p2.
  glm::vec4 baseColor(uint32_t primitive, float u, float v) const;
  // Whether the alpha mask keeps the surface at (u, v) (the light and camera passes' test).
  bool covers(uint32_t primitive, float u, float v) const;
};

// A shadow ray's query context: Embree's, then what the occlusion filter accumulates along the
// ray (Embree hands the filter the context it was given; the struct starts with Embree's).
struct ShadowRayContext {
  RTCIntersectContext embree;
  float transmittance = 1.0f;  // the product of 1 - alpha of the translucent hits so far
};

struct RayScene::Impl {
  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  // Embree's last error message (its error callback writes here for the device's lifetime).
  std::string deviceError;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<RayTexture> textures;
  std::vector<RayMesh> meshes;  // index = Embree geometry id
  size_t triangles = 0;
  double buildSeconds = 0.0;
};

}  // namespace penumbra::truth
