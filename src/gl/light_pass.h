// The light pass: the scene's linear depth from the light, one layer per cascade, into an R32F
// target (with a D32F depth buffer); N-sample textures under MSAA. Owns its targets and keeps
// them while the size, sample count and cascade count stay the same.
#pragma once

#include <span>
#include <vector>

#include "gpu_scene.h"
#include "gpu_timer.h"
#include "linear_depth_maps.h"
#include "penumbra/gl/program.h"
#include "penumbra/image.h"
#include "penumbra/scene.h"
#include "program_cache.h"

namespace penumbra::gl {

struct LightPassShape {
  int size = 0;      // texels per side
  int samples = 1;   // MSAA samples (1: off)
  int cascades = 1;  // array layers
  bool operator==(const LightPassShape&) const = default;
};

// One layer's view: the light's view and the projection of its map.
struct LightLayerView {
  glm::mat4 lightFromWorld{1.0f};
  glm::mat4 clipFromLight{1.0f};
  float nearDistance = 0.0f;
  float farDistance = 1.0f;
  bool perspective = false;
};

class LightPass {
 public:
  LightPass() = default;
  ~LightPass();
  LightPass(const LightPass&) = delete;
  LightPass& operator=(const LightPass&) = delete;

  // (Re)creates the targets when the shape differs from the current one.
  void prepare(const LightPassShape& shape);
  // Draws the scene into layer i with views[i] (views.size() == shape.cascades). Translucent
  // casters cover a dithered alpha share of the texels where `ditherTranslucent` (a technique
  // whose filtering carries it, carriesTranslucency, and the references), else a mask at 0.5.
  void render(ProgramCache& programs, const GpuScene& scene, std::span<const LightLayerView> views,
              bool ditherTranslucent);

  const LightPassShape& shape() const { return shape_; }
  bool multisampled() const { return shape_.samples > 1; }
  // The R32F linear depth: GL_TEXTURE_2D_ARRAY, or _2D_MULTISAMPLE_ARRAY under MSAA.
  unsigned depthTexture() const { return depth_.id(); }
  LinearDepthMaps linearDepth() const {
    return {depth_.id(), shape_.size, shape_.cascades, shape_.samples};
  }
  // One layer's depth (refused under MSAA), row 0 at the bottom.
  Image readDepth(int layer) const;
  // One layer's depth samples, one image channel per sample (MSAA or not), row 0 at the bottom.
  Image readDepthSamples(ProgramCache& programs, int layer) const;
  uint64_t bytes() const;

  GpuTimer timer;

 private:
  void release();
  void checkLayer(int layer) const;

  LightPassShape shape_;
  Texture depth_;
  Texture depthBuffer_;
  std::vector<unsigned> framebuffers_;  // one per layer
};

}  // namespace penumbra::gl
