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

  // Measures the visible view-depth range of this frame (`fallback` where nothing is drawn).
  // `wait`: returns this frame's range, waiting for the GPU. Otherwise waits for nothing and
  // returns the newest range of an earlier frame the GPU has finished (the latency real-time
  // sample-distribution shadow maps run with; the previous frame's wherever the GPU keeps up);
  // only a first measurement, with none before it, waits.
  DepthRange measure(ProgramCache& programs, const GpuScene& scene, const glm::mat4& clipFromWorld,
                     DepthRange projection, int width, int height, DepthRange fallback, bool wait);
  uint64_t bytes() const;
  // Frees the target when depth bounds are no longer fitted (the memory report stays exact),
  // and forgets the ranges measured.
  void release();

 private:
  // One measurement in flight: its result buffer, mapped for reading without a GL call, the
  // fence after its reduction, and the range that stands when it found nothing drawn.
  struct Slot {
    unsigned buffer = 0;
    const uint32_t* bits = nullptr;
    GLsync fence = nullptr;
    DepthRange fallback;
    uint64_t frame = 0;  // which measurement it holds, counting from 1; 0: none
  };

  void allocate(int width, int height);
  // Whether the slot's measurement is done, waiting for it or not; reads it into latest_.
  bool collect(Slot& slot, bool wait);

  int width_ = 0, height_ = 0;
  Texture depth_;
  unsigned framebuffer_ = 0;
  std::array<Slot, kDepthBoundsMeasurementsInFlight> slots_{};
  uint64_t measured_ = 0;  // measurements started
  std::optional<DepthRange> latest_;
  uint64_t latestFrame_ = 0;
};

}  // namespace penumbra::gl
