// Shared render options.
#include "render_options.h"

#include <algorithm>

#include "penumbra/error.h"
#include "shared/filter_weights.h"

namespace penumbra::cli {

void addRenderOptions(CLI::App& app, RenderOptions& o) {
  app.add_option("--shadow-size", o.shadowSize, "shadow-map texels per side")
      ->capture_default_str();
  app.add_option("--msaa", o.msaa, "light-pass samples: 1 (off), 2, 4, 8")->capture_default_str();
  app.add_option("--blur", o.blurTaps,
                 "prefilter width in taps (odd; 1 = none); the summed-area filter's smallest box")
      ->capture_default_str();
  app.add_option("--blur-kernel", o.blurKernel, "gaussian or box")->capture_default_str();
  app.add_option("--blur-sigma", o.blurSigma, "Gaussian sigma in texels (default: radius/2)");
  app.add_option("--filter", o.filter, "point, bilinear, trilinear, anisotropic or sat")
      ->capture_default_str();
  app.add_option("--aniso", o.aniso, "anisotropy for the anisotropic filter, 1..16")
      ->capture_default_str();
  app.add_option("--width", o.width, "frame width in pixels")->capture_default_str();
  app.add_option("--height", o.height, "frame height in pixels")->capture_default_str();
  app.add_option("--normal-offset", o.normalOffset, "normal-offset bias in shadow-map texels")
      ->capture_default_str();
}

gl::RenderSettings toRenderSettings(const RenderOptions& o) {
  gl::RenderSettings s;
  s.shadowMapSize = o.shadowSize;
  s.msaaSamples = o.msaa;
  if (o.blurTaps < 1 || o.blurTaps % 2 == 0) {
    throw Error("blur taps " + std::to_string(o.blurTaps) +
                ": give an odd kernel width (1 = no blur, 3, 5, 7, ... " +
                std::to_string(2 * shaders::kMaxBlurRadius + 1) + ")");
  }
  s.blur.radius = (o.blurTaps - 1) / 2;
  if (o.blurKernel != "gaussian" && o.blurKernel != "box") {
    throw Error("unknown blur kernel '" + o.blurKernel + "'; valid kernels: gaussian, box");
  }
  s.blur.kernel = o.blurKernel == "box" ? BlurKernel::Box : BlurKernel::Gaussian;
  s.blur.sigma = o.blurSigma > 0.0f ? o.blurSigma : std::max(0.5f, 0.5f * float(s.blur.radius));
  s.filter = parseFilterMode(o.filter);
  s.anisotropy = o.aniso;
  s.width = o.width;
  s.height = o.height;
  s.normalOffsetTexels = o.normalOffset;
  return s;
}

}  // namespace penumbra::cli
