// The CPU's filtered reference per pixel, cascade by cascade.
#include "penumbra/gl/cascaded_reference.h"

#include <glm/glm.hpp>
#include <string>

#include "penumbra/error.h"

namespace penumbra::gl {

CascadedReference::CascadedReference(const RenderResult& frame, int shadowMapSize,
                                     FilterMode filter, int anisotropy, HalfRounding halfRounding,
                                     DepthOfCascade depthOfCascade)
    : frame_(frame),
      shadowMapSize_(shadowMapSize),
      filter_(filter),
      anisotropy_(anisotropy),
      halfRounding_(halfRounding),
      depthOfCascade_(std::move(depthOfCascade)) {}

const CpuShadowLookup& CascadedReference::twin(int cascade) {
  std::unique_ptr<CpuShadowLookup>& found = twins_[cascade];
  if (!found) {
    if (cascade < 0 || size_t(cascade) >= frame_.cascadeBlurs.size()) {
      throw Error("the render has no shadow map for cascade " + std::to_string(cascade));
    }
    found = std::make_unique<CpuShadowLookup>(
        depthOfCascade_(cascade), LookupConfig{.technique = Technique::Hard,
                            .params = frame_.params,
                            .filter = filter_,
                            .blur = frame_.cascadeBlurs[size_t(cascade)],
                            .anisotropy = anisotropy_,
                            .halfRounding = halfRounding_,
                            .kernelScale = frame_.cascadeFrame.kernelScale(cascade, shadowMapSize_)});
  }
  return *found;
}

float CascadedReference::visibilityAt(int x, int y) {
  const int cascade = int(frame_.cascades.at(x, y, 0));
  const float blend = frame_.cascades.at(x, y, 1);
  const LookupPixel pixel = lookupPixelAt(frame_, x, y);
  float v = twin(cascade).referenceVisibility(pixel);
  if (blend > 0.0f && cascade + 1 < frame_.cascadeFrame.count) {
    const LookupPixel other =
        lookupPixelInNextCascade(pixel, frame_.cascadeFrame, cascade, shadowMapSize_);
    v = glm::mix(v, twin(cascade + 1).referenceVisibility(other), blend);
  }
  return v;
}

}  // namespace penumbra::gl
