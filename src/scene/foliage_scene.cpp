// Foliage: leaf cards (textured quads whose alpha masks out everything but the leaves), the case
// where a shadow is mostly holes and filtered shadow maps matter most (sub-texel gaps between
// leaves alias under a hard test).
#include "foliage_scene.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "mesh_builder.h"

namespace penumbra::scene {
namespace {

// One double-sided card facing `normal`, `halfSize` across, texture corners (0,0)-(1,1).
void addCard(Mesh& mesh, glm::vec3 centre, glm::vec3 right, glm::vec3 up, float halfSize) {
  const glm::vec3 normal = glm::normalize(glm::cross(right, up));
  const uint32_t base = uint32_t(mesh.vertices.size());
  const glm::vec3 r = right * halfSize, u = up * halfSize;
  mesh.vertices.push_back({centre - r + u, normal, {0.0f, 0.0f}});
  mesh.vertices.push_back({centre + r + u, normal, {1.0f, 0.0f}});
  mesh.vertices.push_back({centre + r - u, normal, {1.0f, 1.0f}});
  mesh.vertices.push_back({centre - r - u, normal, {0.0f, 1.0f}});
  for (uint32_t i : {0u, 3u, 2u, 0u, 2u, 1u}) mesh.indices.push_back(base + i);
}

// A card of random orientation: its plane spanned by two random orthonormal directions.
void addRandomCard(Mesh& mesh, glm::vec3 centre, float halfSize, std::mt19937& rng) {
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  glm::vec3 a(gauss(rng), gauss(rng), gauss(rng));
  glm::vec3 b(gauss(rng), gauss(rng), gauss(rng));
  a = glm::normalize(a);
  b = glm::normalize(b - glm::dot(a, b) * a);
  addCard(mesh, centre, a, b, halfSize);
}

Mesh leafMesh() {
  Mesh leaves = makeMesh(glm::vec3(1.0f));  // the texture carries the colour
  leaves.baseColorTexture = 0;
  leaves.alphaMode = AlphaMode::Mask;
  leaves.alphaCutoff = 0.5f;
  leaves.doubleSided = true;
  return leaves;
}

}  // namespace

TextureImage makeLeafTexture(int size) {
  TextureImage t;
  t.name = "generated leaf cluster";
  t.width = t.height = size;
  t.rgba.assign(size_t(size) * size_t(size) * 4, 0);
  // Seven leaves around the centre: ellipses of half-length 0.2 and half-width 0.075 (in units
  // of the texture side), pointing out at even angles, each with a darker midrib.
  constexpr int kLeaves = 7;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const glm::vec2 p((float(x) + 0.5f) / float(size) - 0.5f,
                        (float(y) + 0.5f) / float(size) - 0.5f);
      uint8_t* texel = &t.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4];
      for (int leaf = 0; leaf < kLeaves; ++leaf) {
        const float angle = 2.0f * float(M_PI) * (float(leaf) + 0.25f) / float(kLeaves);
        const glm::vec2 along(std::cos(angle), std::sin(angle));
        const glm::vec2 across(-along.y, along.x);
        const glm::vec2 q = p - 0.25f * along;  // leaf centre a quarter out from the middle
        const float u = glm::dot(q, along) / 0.2f, v = glm::dot(q, across) / 0.075f;
        if (u * u + v * v > 1.0f) continue;
        const bool midrib = std::abs(v) < 0.12f;
        const float shade = 0.75f + 0.25f * float(leaf % 3) / 2.0f;
        texel[0] = uint8_t((midrib ? 70.0f : 60.0f) * shade);
        texel[1] = uint8_t((midrib ? 120.0f : 150.0f) * shade);
        texel[2] = uint8_t((midrib ? 40.0f : 45.0f) * shade);
        texel[3] = 255;
      }
    }
  }
  return t;
}

Scene makeFoliageScene() {
  Scene s;
  s.name = "foliage";
  s.description =
      "a tree crown and a hedge of alpha-masked leaf cards over ground: shadows made of holes";
  Mesh ground = makeMesh(glm::vec3(0.75f, 0.72f, 0.65f));
  addGround(ground, glm::vec3(0.0f), 8.0f);
  s.meshes.push_back(std::move(ground));
  Mesh trunk = makeMesh(glm::vec3(0.45f, 0.33f, 0.22f));
  addCylinder(trunk, glm::vec3(-1.2f, 0.0f, -0.8f), 0.1f, 2.4f);
  s.meshes.push_back(std::move(trunk));

  std::mt19937 rng(20240611u);  // fixed: the scene is the same on every run
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  Mesh crown = leafMesh();
  const glm::vec3 crownCentre(-1.2f, 2.6f, -0.8f);
  for (int i = 0; i < 160; ++i) {
    glm::vec3 offset;
    do {
      offset = glm::vec3(unit(rng), unit(rng), unit(rng));
    } while (glm::dot(offset, offset) > 1.0f);
    addRandomCard(crown, crownCentre + offset * glm::vec3(1.1f, 0.7f, 1.1f), 0.32f, rng);
  }
  s.meshes.push_back(std::move(crown));
  // The hedge: upright and tilted cards along x, 0.9 m high.
  Mesh hedge = leafMesh();
  for (int i = 0; i < 90; ++i) {
    const glm::vec3 centre(1.6f * unit(rng) + 1.4f, 0.45f + 0.35f * unit(rng),
                           1.2f + 0.25f * unit(rng));
    addRandomCard(hedge, centre, 0.22f, rng);
  }
  s.meshes.push_back(std::move(hedge));
  s.textures.push_back(makeLeafTexture(256));

  s.camera = {glm::vec3(0.8f, 3.6f, 6.5f), glm::vec3(0.0f, 0.6f, 0.0f), 45.0f};
  s.light.kind = LightKind::Directional;
  s.light.direction = glm::normalize(glm::vec3(0.45f, -1.0f, 0.35f));
  return s;
}

}  // namespace penumbra::scene
