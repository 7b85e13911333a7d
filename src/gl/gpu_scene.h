// A scene's meshes in GL buffers, uploaded once: one vertex array, drawn mesh by mesh with each
// mesh's material.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra::gl {

class GpuScene {
 public:
  struct Material {
    glm::vec3 albedo{0.8f};
  };

  explicit GpuScene(const Scene& scene);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Draws every mesh; `beforeMesh` runs first for each (to set its material).
  void draw(const std::function<void(const Material&)>& beforeMesh) const;
  uint64_t bytes() const { return bytes_; }

 private:
  struct Range {
    size_t firstIndex;
    size_t indexCount;
    int baseVertex;
  };
  unsigned vertexArray_ = 0;
  unsigned vertexBuffer_ = 0;
  unsigned indexBuffer_ = 0;
  std::vector<Range> ranges_;
  std::vector<Material> materials_;
  uint64_t bytes_ = 0;
};

// A 64-bit FNV-1a hash of what GpuScene uploads (geometry and materials): equal scenes hash
// equal, so a renderer re-uploads only a scene whose content changed.
uint64_t sceneFingerprint(const Scene& scene);

}  // namespace penumbra::gl
