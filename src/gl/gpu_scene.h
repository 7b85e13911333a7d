// A scene's meshes in GL buffers: one vertex array, drawn mesh by mesh.
#pragma once

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

  // Draws every mesh; `beforeMesh` runs first for each (to set its albedo).
  void draw(const std::function<void(const Mesh&)>& beforeMesh) const;

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
  const Scene& scene_;
};

}  // namespace penumbra::gl
