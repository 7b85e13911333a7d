// The camera pass's per-pixel shadow lookup on the CPU: the twin of the GPU's, running the same
// shared code (shared/shadow_lookup.h, shared/filtered_reference.h) over channels built by the
// CPU reference filters (encode, blur, mips, summed-area table, Z-max pyramid, each rounded to
// the technique's storage format as the GPU's textures are; PCF and the hard test read the depth
// itself, as the renderer's do, and have none). Only texture access differs, so the
// GPU renderer can be tested pixel by pixel against it (tests/gl/lookup_parity_test.cpp).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "penumbra/filter_mode.h"
#include "penumbra/filters.h"
#include "penumbra/image.h"
#include "penumbra/storage_format.h"
#include "penumbra/technique.h"
#include "penumbra/shared/soft_shadow.h"

namespace penumbra {

namespace shaders {
struct CpuLookupTextures;
}

struct LookupConfig {
  Technique technique = Technique::Vsm;
  TechniqueParams params = defaultTechniqueParams();  // as rendered (LVSM's splits as placed)
  FilterMode filter = FilterMode::Bilinear;
  BlurSpec blur{BlurKernel::Box, 2, 1.0f};  // prefilter; with `SummedArea`, the smallest box
  int anisotropy = 16;                      // [1, 16]
  HalfRounding halfRounding = HalfRounding::Nearest;  // the device's (Renderer::halfFloatRounding)
  // Cascades: cascade 0's texel over this cascade's, so PCF keeps its kernel's world width
  // (shared/cascade_selection.h); 1 for one map or cascade 0.
  float kernelScale = 1.0f;
  // The light's size and depth metric (shared/soft_shadow.h): size 0 (the default) casts hard
  // shadows; otherwise PCF is PCSS and the filterable techniques filter over the penumbra.
  shaders::SoftLight softLight{0.0f, 0, 0.0f, 1.0f, 1.0f, shaders::kMaxSoftWidthTexels};
};

// One pixel's lookup inputs, as the camera pass computes them (RenderResult::lookup,
// receiverPlane and uvDerivatives hold them per pixel).
struct LookupPixel {
  glm::vec2 uv{0.5f};
  float receiverDepth = 0.5f;  // linear light-space depth (clamped to [0,1] by the lookup)
  glm::vec2 uvDx{0.0f};
  glm::vec2 uvDy{0.0f};
  glm::vec2 depthPerTexel{0.0f};  // receiver plane's depth gradient per shadow-map texel
};

struct LookupSample {
  float visibility = 1.0f;
  float diagnostic = 0.0f;  // ESM: 1 where classification failed; LVSM: the layer; else 0
};

class CpuShadowLookup {
 public:
  // depth: the light pass's linear depth, square, one channel, row 0 at the bottom (GL's).
  // Single-sampled: the GPU's MSAA encode (moments of every sample) is not modelled.
  CpuShadowLookup(const Image& depth, const LookupConfig& config);
  ~CpuShadowLookup();
  CpuShadowLookup(const CpuShadowLookup&) = delete;
  CpuShadowLookup& operator=(const CpuShadowLookup&) = delete;

  // What the technique's camera-pass lookup returns for the pixel.
  LookupSample lookup(const LookupPixel& pixel) const;
  // The filtered reference for the pixel (docs/reference.md). Mip-mapped filter modes need a
  // power-of-two map size (throws Error otherwise).
  float referenceVisibility(const LookupPixel& pixel) const;
  // Whether the GPU's camera pass leaves the pixel's reference to this twin: its kernel needs
  // more texel tests than one shader invocation may loop over (shaders::referenceLeftToCpu).
  bool referenceLeftToCpu(const LookupPixel& pixel) const;

  // The filtered channels the technique's reconstruction reads for the pixel, channel c at index
  // c (channels it does not read are 0); empty for PCF and the hard test, which filter after the
  // depth test. What the GPU's texture unit returns for the same lookup, but for rounding.
  std::vector<float> filteredChannels(const LookupPixel& pixel) const;

 private:
  std::unique_ptr<shaders::CpuLookupTextures> textures_;
  LookupConfig config_;
};

}  // namespace penumbra
