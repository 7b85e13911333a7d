// Sample-distribution depth bounds (Lauritzen et al. 2011): the nearest and farthest view depth
// the camera actually sees, from a depth-only camera pass reduced on the GPU, so cascades split
// only the depths that hold visible surfaces.
#pragma once

#include <optional>

#include "gpu_scene.h"
#include "penumbra/cascades.h"
#include "penumbra/gl/program.h"
#include "program_cache.h"

namespace penumbra::gl {

class DepthBoundsPass {
 public:
  DepthBoundsPass() = default;
  ~DepthBoundsPass();
  DepthBoundsPass(const DepthBoundsPass&) = delete;
  DepthBoundsPass& operator=(const DepthBoundsPass&) = delete;

  // The visible view-depth range, or `fallback` when nothing is drawn.
  DepthRange measure(ProgramCache& programs, const GpuScene& scene, const glm::mat4& clipFromWorld,
                     DepthRange projection, int width, int height, DepthRange fallback);
  uint64_t bytes() const;
  // Frees the target when depth bounds are no longer fitted (the memory report stays exact).
  void release();

 private:
  int width_ = 0, height_ = 0;
  Texture depth_;
  unsigned framebuffer_ = 0;
  std::optional<Buffer> bounds_;
};

}  // namespace penumbra::gl
