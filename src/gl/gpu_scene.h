// A scene in GL objects, uploaded once: one vertex and one index buffer for all meshes, and each
// base-colour texture as sRGB with mipmaps; drawn mesh by mesh.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra::gl {

class GpuScene {
 public:
  explicit GpuScene(const Scene& scene);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Draws every mesh; `beforeMesh` runs first for each (to set its material). The mesh's
  // base-colour texture, if any, is bound to `textureUnit`.
  void draw(const std::function<void(const Mesh&)>& beforeMesh, unsigned textureUnit) const;

  // Bytes of the vertex, index and texture storage (textures with their full mip chains).
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
  std::vector<unsigned> textures_;
  std::vector<Range> ranges_;
  uint64_t bytes_ = 0;
  const Scene& scene_;
};

}  // namespace penumbra::gl
