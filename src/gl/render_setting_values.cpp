// The render settings' names and device-independent ranges.
#include "penumbra/gl/render_setting_values.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "penumbra/error.h"
#include "renderer_state.h"

namespace penumbra::gl {
namespace {

// Looks `name` up among `values` by `nameOf`; throws Error listing the valid names.
template <typename T, size_t N, typename NameOf>
T parseName(std::string_view name, const T (&values)[N], NameOf nameOf, const char* what,
            const char* plural) {
  std::string valid;
  for (const T& v : values) {
    if (nameOf(v) == name) return v;
    valid += (valid.empty() ? "" : ", ") + std::string(nameOf(v));
  }
  throw Error("unknown " + std::string(what) + " '" + std::string(name) + "'; valid " + plural +
              ": " + valid);
}

constexpr BlurKernel kBlurKernels[] = {BlurKernel::Gaussian, BlurKernel::Box};
constexpr Overlay kOverlays[] = {Overlay::None, Overlay::Cascades};
constexpr bool kCascadeDepths[] = {false, true};

}  // namespace

void checkMsaaSamples(int samples) {
  if (samples != 1 && samples != 2 && samples != 4 && samples != 8) {
    throw Error("MSAA samples " + std::to_string(samples) + ": valid values are 1 (off), 2, 4, 8");
  }
}

int blurRadiusOfTaps(int taps) {
  if (taps < 1 || taps > kMaxBlurTaps || taps % 2 == 0) {
    throw Error("blur taps " + std::to_string(taps) +
                ": give an odd kernel width (1 = no blur, 3, 5, 7, ... " +
                std::to_string(kMaxBlurTaps) + ")");
  }
  return (taps - 1) / 2;
}

float defaultBlurSigma(int radius) {
  return std::max(0.5f, 0.5f * float(radius));
}

float checkedBlurSigma(float sigma) {
  checkRange("blur sigma", sigma, kMinBlurSigma, kMaxBlurSigma);
  return sigma;
}

std::string_view blurKernelName(BlurKernel kernel) {
  return kernel == BlurKernel::Box ? "box" : "gaussian";
}

BlurKernel parseBlurKernel(std::string_view name) {
  return parseName(name, kBlurKernels, blurKernelName, "blur kernel", "kernels");
}

std::string_view overlayName(Overlay overlay) {
  return overlay == Overlay::Cascades ? "cascades" : "none";
}

Overlay parseOverlay(std::string_view name) {
  return parseName(name, kOverlays, overlayName, "overlay", "overlays");
}

std::string_view cascadeDepthName(bool fitDepthBounds) {
  return fitDepthBounds ? "fitted" : "fixed";
}

bool parseCascadeDepth(std::string_view name) {
  return parseName(name, kCascadeDepths, cascadeDepthName, "cascade depth", "depths");
}

void validateRenderSettings(const RenderSettings& s) {
  checkRange("shadow-map size", s.shadowMapSize, kMinShadowMapSize, kMaxTextureSizeAnyGl);
  checkRange("frame width", s.width, kMinFrameSize, kMaxTextureSizeAnyGl);
  checkRange("frame height", s.height, kMinFrameSize, kMaxTextureSizeAnyGl);
  checkMsaaSamples(s.msaaSamples);
  checkRange("blur radius", s.blur.radius, 0, shaders::kMaxBlurRadius);
  checkedBlurSigma(s.blur.sigma);
  checkRange("anisotropy", s.anisotropy, 1, kMaxAnisotropy);
  checkRange("normal offset (texels)", s.normalOffsetTexels, 0.0f, kMaxNormalOffsetTexels);
  checkRange("ambient", s.ambient, 0.0f, 1.0f);
  validateCascadeSettings(s.cascades);
}

}  // namespace penumbra::gl
