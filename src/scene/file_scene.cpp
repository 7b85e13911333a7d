// Checks and defaults shared by the glTF and OBJ loaders.
#include "file_scene.h"

#include <algorithm>
#include <cmath>

#include "penumbra/error.h"

namespace penumbra::scene {
namespace {

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 triangleNormal(const Mesh& mesh, size_t firstIndex) {
  const glm::vec3 a = mesh.vertices[mesh.indices[firstIndex]].position;
  const glm::vec3 b = mesh.vertices[mesh.indices[firstIndex + 1]].position;
  const glm::vec3 c = mesh.vertices[mesh.indices[firstIndex + 2]].position;
  return glm::cross(b - a, c - a);  // length: twice the area
}

// A unit normal for `n`, or +y where it has no direction (a degenerate triangle: it covers no
// pixel, its normal only has to be finite).
glm::vec3 unitOrUp(glm::vec3 n) {
  const float length = glm::length(n);
  return length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
}

// Area-weighted triangle normals for the vertices whose own normal is unusable.
size_t repairNormals(Mesh& mesh) {
  std::vector<bool> bad(mesh.vertices.size());
  size_t count = 0;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::vec3 n = mesh.vertices[i].normal;
    const float length = glm::length(n);
    bad[i] = !finite(n) || !(length > 1e-6f) || !std::isfinite(length);
    if (bad[i]) {
      mesh.vertices[i].normal = glm::vec3(0.0f);
      ++count;
    } else {
      mesh.vertices[i].normal = n / length;
    }
  }
  if (count == 0) return 0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 n = triangleNormal(mesh, t);
    if (!finite(n)) continue;
    for (size_t k = 0; k < 3; ++k) {
      if (bad[mesh.indices[t + k]]) mesh.vertices[mesh.indices[t + k]].normal += n;
    }
  }
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (bad[i]) mesh.vertices[i].normal = unitOrUp(mesh.vertices[i].normal);
  }
  return count;
}

}  // namespace

void computeFlatNormals(Mesh& mesh) {
  Mesh flat = mesh;
  flat.vertices.clear();
  flat.indices.clear();
  flat.vertices.reserve(mesh.indices.size());
  flat.indices.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 n = unitOrUp(triangleNormal(mesh, t));
    for (size_t k = 0; k < 3; ++k) {
      Vertex v = mesh.vertices[mesh.indices[t + k]];
      v.normal = n;
      flat.indices.push_back(uint32_t(flat.vertices.size()));
      flat.vertices.push_back(v);
    }
  }
  mesh = std::move(flat);
}

void finishFileScene(Scene& scene, const std::string& source, const FileView& view) {
  size_t repaired = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    Mesh& mesh = scene.meshes[m];
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      const Vertex& v = mesh.vertices[i];
      if (!finite(v.position)) {
        throw Error(source + ": a vertex position is not finite (mesh " + std::to_string(m) +
                    ", vertex " + std::to_string(i) + ": " + std::to_string(v.position.x) + ", " +
                    std::to_string(v.position.y) + ", " + std::to_string(v.position.z) + ")");
      }
      if (!std::isfinite(v.texcoord.x) || !std::isfinite(v.texcoord.y)) {
        throw Error(source + ": a texture coordinate is not finite (mesh " + std::to_string(m) +
                    ", vertex " + std::to_string(i) + ")");
      }
    }
    repaired += repairNormals(mesh);
  }
  if (repaired > 0) {
    scene.warnings.push_back(source + ": " + std::to_string(repaired) +
                             " vertex normals were not finite or had zero length; replaced by "
                             "their triangles' normals");
  }
  if (scene.triangleCount() == 0) throw Error(source + ": the scene has no triangles to render");

  const Bounds bounds = scene.bounds();
  if (!finite(bounds.max - bounds.min) || !std::isfinite(bounds.radius())) {
    throw Error(source + ": the scene's extent is not finite in single precision");
  }
  const float radius = std::max(bounds.radius(), 1e-3f);
  scene.fileCameras = view.cameras;
  scene.camera = view.cameras.empty() ? framingCamera(scene, 16.0f / 9.0f) : view.cameras[0].camera;
  if (view.light) {
    scene.light = *view.light;
  } else {
    scene.light.kind = LightKind::Directional;
    scene.light.direction = glm::normalize(glm::vec3(0.35f, -1.0f, -0.45f));
  }
  // About a pixel per frame at the framing view, as the built-in scenes' paths.
  scene.pathOffset = glm::vec3(0.002f * radius, 0.0f, 0.0f);
}

}  // namespace penumbra::scene
