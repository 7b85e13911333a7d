// Sample-distribution depth bounds (Lauritzen et al. 2011): the nearest and farthest view depth
// the camera actually sees, from a depth-only camera pass reduced on the GPU, so cascades split
// only the depths that hold visible surfaces.
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <cstdint>
#include <optional>

#include "gpu_scene.h"
#include "memory_plan.h"
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

  // Measures the visible view-depth range of this frame (the projection's range where nothing is
  // drawn). `wait`: returns this frame's range, waiting for the GPU. Otherwise returns the
  // previous measurement's, one frame late as real-time sample-distribution shadow maps run:
  // always that one, so that the same frames render alike whatever the GPU's pace, and without
  // a wait wherever the GPU keeps a frame's pace. A first measurement, with none before it,
  // waits for its own.
  DepthRange measure(ProgramCache& programs, const GpuScene& scene, const glm::mat4& clipFromWorld,
                     DepthRange projection, int width, int height, bool wait);
  uint64_t bytes() const;
  // Frees the target when depth bounds are no longer fitted (the memory report stays exact),
  // and forgets the ranges measured.
  void release();
  // Forgets the ranges measured (a new scene's frames must not take the old one's).
  void forget();

 private:
  // One measurement: its result buffer, mapped for reading without a GL call, the fence after
  // its reduction, the range that stands when it finds nothing drawn, and once read, its range.
  struct Slot {
    unsigned buffer = 0;
    const uint32_t* bits = nullptr;
    GLsync fence = nullptr;
    DepthRange projection;
    std::optional<DepthRange> range;
  };

  void allocate(int width, int height);
  // The slot's range, once its fence has signalled: a poll first, a wait only if it has not.
  DepthRange collect(Slot& slot);

  int width_ = 0, height_ = 0;
  Texture depth_;
  unsigned framebuffer_ = 0;
  std::array<Slot, kDepthBoundsMeasurementsInFlight> slots_{};  // this frame's and the previous
  uint64_t measured_ = 0;  // measurements started since the last forget()
};

}  // namespace penumbra::gl
