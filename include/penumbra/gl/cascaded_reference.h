// The filtered reference of one pixel on the CPU: the hard test filtered with the lookup's kernel
// by the CPU twin (CpuShadowLookup) of the pixel's cascade, blended with the next cascade's in
// the blend band, exactly as the camera pass's reference path does. One implementation for the
// renderer (the pixels whose kernel is too wide for one shader invocation) and the viewer (its
// background reference).
#pragma once

#include <functional>
#include <map>
#include <memory>

#include "penumbra/gl/renderer.h"
#include "penumbra/shadow_lookup.h"

namespace penumbra::gl {

class CascadedReference {
 public:
  // Cascade c's linear light-space depth map (square, one channel), read when first needed.
  using DepthOfCascade = std::function<Image(int cascade)>;

  // `frame` (its lookup inputs, cascades, params and blurs) must outlive this object.
  CascadedReference(const RenderResult& frame, int shadowMapSize, FilterMode filter,
                    int anisotropy, HalfRounding halfRounding, DepthOfCascade depthOfCascade);

  // The reference visibility of pixel (x, y), which must lie in a cascade (cascades >= 0).
  // Builds each cascade's twin once; not thread-safe.
  float visibilityAt(int x, int y);

 private:
  const CpuShadowLookup& twin(int cascade);

  const RenderResult& frame_;
  int shadowMapSize_;
  FilterMode filter_;
  int anisotropy_;
  HalfRounding halfRounding_;
  DepthOfCascade depthOfCascade_;
  std::map<int, std::unique_ptr<CpuShadowLookup>> twins_;
};

}  // namespace penumbra::gl
