// The renderer's passes and the device facts it checks settings against. Each pass owns its GL
// resources (docs/renderer.md); the renderer only orders them.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "auxiliary_passes.h"
#include "camera_pass.h"
#include "depth_bounds_pass.h"
#include "gpu_scene.h"
#include "gpu_timer.h"
#include "light_pass.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/storage_format.h"
#include "program_cache.h"
#include "shadow_filter_state.h"
#include "shadow_map_filter.h"

namespace penumbra::gl {

// Throw Error "<what> <value> is out of range [lo, hi]" (renderer.cpp).
void checkRange(std::string_view what, float value, float lo, float hi);
void checkRange(std::string_view what, int value, int lo, int hi);

// The frame's limits (the shadow map's are the filter's: ShadowFilter::State).
struct DeviceLimits {
  std::string device;
  int maxTextureSize = 0;
  int maxArrayLayers = 0;
  HalfRounding halfRounding = HalfRounding::Nearest;  // how image stores round to fp16
};

struct Renderer::State {
  DeviceLimits limits;
  uint64_t memoryLimit = 0;  // Renderer::limitMemory; 0: none
  ProgramCache programs;

  std::unique_ptr<GpuScene> scene;
  uint64_t sceneFingerprint = 0;
  uint64_t sceneLayoutFingerprint = 0;  // sceneLayoutFingerprint: a new pose updates vertices
  ViewBounds viewBounds;  // the frame's depth ranges and the light's fit (Scene::viewBounds)
  Scene sceneDefaults;    // name, camera and light of the uploaded scene (no meshes)

  DepthBoundsPass depthBounds;
  LightPass light;
  // Encode, prefilter, mips or summed-area table, ESM's Z-max pyramid, LVSM's placement: the
  // public filtering API, the renderer its first host (penumbra/gl/shadow_filter.h).
  ShadowFilter shadows;
  CameraPass camera;
  std::optional<Texture> uploadedDepth;  // filterDepthMap's input
  GpuTimer depthBoundsTimer;

  RenderSettings settings;  // of the last frame
  FrameGeometry frame;      // of the last frame
  // Whether the last frame was a technique's (Renderer::render): not a reference's, an area
  // light's samples or filterDepthMap's, whose camera pass timeCameraPass must not draw again.
  bool techniqueFrame = false;
  std::vector<BlurSpec> cascadeBlurs;

  MemoryReport memory() const;
};

}  // namespace penumbra::gl
