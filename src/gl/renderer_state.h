// The renderer's GL objects, shared by its pass files (renderer.cpp, shadow_map_filter.cpp).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gpu_timer.h"
#include "penumbra/channel_layout.h"
#include "penumbra/gl/program.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/shader_library.h"
#include "penumbra/storage_format.h"

namespace penumbra::gl {

class GpuScene;

struct Renderer::State {
  ShaderLibrary library;
  std::map<std::string, Program> programs;
  std::string device;
  int maxTextureSize = 0;
  int maxArrayLayers = 0;
  uint64_t memoryLimit = 0;  // Renderer::limitMemory; 0: none
  int maxSamples = 0;
  float maxAnisotropy = 1.0f;
  HalfRounding halfRounding = HalfRounding::Nearest;  // how image stores round to fp16

  // Light pass.
  Texture lightDepth;   // linear depth R32F (2D or 2D multisample)
  Texture lightBuffer;  // depth buffer D32F
  unsigned lightFramebuffer = 0;
  int shadowMapSize = 0;
  int msaaSamples = 1;

  // Technique channels and prefilter.
  ChannelLayout layout;
  Texture channels;  // 2D array, layout.layers layers, channelLevels levels
  Texture scratch;   // 2D array, one level: the blur's intermediate
  int channelLevels = 1;
  std::optional<Buffer> paramsBlock;
  std::optional<Buffer> satRows;
  std::optional<Buffer> satStats;
  std::optional<Buffer> satSums;
  std::optional<Texture> uploadedDepth;  // filterDepthMap's input
  TechniqueParams params;                // the parameters in use (LVSM splits placed)

  // Auxiliary passes: ESM's Z-max pyramid, LVSM's Lloyd samples.
  Texture zmax;  // 2D array, one R32F layer, full mip chain
  int zmaxLevels = 0;
  std::optional<Buffer> splitSamples;

  // Camera pass.
  Texture frameColor;
  Texture frameVisibility;
  Texture frameDiagnostic;
  Texture frameLookup;
  Texture frameReceiverPlane;
  Texture frameDerivatives;
  Texture frameDepth;
  unsigned frameFramebuffer = 0;

  GpuTimer lightTimer, encodeTimer, prefilterTimer, mipsTimer, auxiliaryTimer, cameraTimer;
  RenderSettings settings;

  ~State();

  // A compiled program for these sources and defines, specialised to the current technique
  // (TECHNIQUE_ID), built on first use.
  const Program& graphics(const std::string& vertex, const std::string& fragment,
                          const std::vector<ShaderDefine>& defines);
  const Program& compute(const std::string& path, const std::vector<ShaderDefine>& defines);

  // Binds the technique's parameter block for the passes that run shared math.
  void bindParameters() const;
  // Uploads `params` to the parameter block.
  void uploadParameters();
};

// shadow_map_filter.cpp: encode -> blur -> mips or summed-area table, on lightDepth (or the
// texture bound as input) into `channels`.
void allocateChannels(Renderer::State& state, const RenderSettings& settings);
void encodeChannels(Renderer::State& state, unsigned depthTexture, bool multisampled);
void prefilterChannels(Renderer::State& state);
// Fills levels 1..levels-1 of a 2D-array texture of `layout` from level 0 with `reduce`
// (passes/mip_reduce.comp in the layout's image format).
void reduceMipLevels(Renderer::State& state, const Program& reduce, const Texture& texture,
                     const ChannelLayout& layout, int levels);

// frame_passes.cpp: render targets, the light pass, the camera pass (or the filtered reference).
void allocateLightPass(Renderer::State& state);
void allocateFrame(Renderer::State& state, int width, int height);
void renderLightPass(Renderer::State& state, const GpuScene& gpuScene, const LightView& light);
void renderCameraPass(Renderer::State& state, const Scene& scene, const GpuScene& gpuScene,
                      const LightView& light, bool reference = false);

// auxiliary_passes.cpp.
void buildZmaxPyramid(Renderer::State& state, unsigned depthTexture, bool multisampled);
void placeLayersByLloyd(Renderer::State& state, unsigned depthTexture, bool multisampled);
std::vector<SplitSample> readSplitSamplesBuffer(const Renderer::State& state);

}  // namespace penumbra::gl
