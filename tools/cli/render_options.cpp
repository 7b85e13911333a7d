// Shared render options.
#include "render_options.h"

#include <algorithm>

#include "penumbra/error.h"
#include "penumbra/gl/render_setting_values.h"

namespace penumbra::cli {

void addRenderOptions(CLI::App& app, RenderOptions& o) {
  app.add_option("--shadow-size", o.shadowSize, "shadow-map texels per side")
      ->capture_default_str();
  app.add_option("--msaa", o.msaa, "light-pass samples: 1 (off), 2, 4, 8")->capture_default_str();
  app.add_option("--blur", o.blurTaps,
                 "prefilter width in taps (odd; 1 = none); the summed-area filter's smallest box")
      ->capture_default_str();
  app.add_option("--blur-kernel", o.blurKernel, "gaussian or box")->capture_default_str();
  app.add_option("--blur-sigma", o.blurSigma,
                 "Gaussian sigma in texels, [0.01, 64] (default: half the radius, at least 0.5)");
  app.add_option("--filter", o.filter,
                 "point, bilinear, trilinear, anisotropic (every channel through the probes the "
                 "reference models), anisotropic-driver (the driver's own filter) or sat")
      ->capture_default_str();
  app.add_option("--aniso", o.aniso, "anisotropy for the anisotropic filter, 1..16")
      ->capture_default_str();
  app.add_option("--width", o.width, "frame width in pixels")->capture_default_str();
  app.add_option("--height", o.height, "frame height in pixels")->capture_default_str();
  app.add_option("--normal-offset", o.normalOffset, "normal-offset bias in shadow-map texels")
      ->capture_default_str();
  app.add_option("--cascades", o.cascades,
                 "cascaded shadow maps for the directional light, 1..8 (1: one map of the scene)")
      ->capture_default_str();
  // The options that tune cascades need more than one (from --cascades or a settings file):
  // checked once the count is known (requireGivenOptionsApply), never silently ignored.
  auto tunesCascades = [&o](CLI::Option* option) {
    option->each([&o](const std::string&) { o.cascadesTuned = true; });
    return option;
  };
  CLI::Option* lambda =
      tunesCascades(app.add_option("--cascade-lambda", o.cascadeLambda,
                                   "practical split scheme: 0 uniform .. 1 logarithmic (PSSM)")
                        ->capture_default_str());
  tunesCascades(app.add_option("--cascade-splits", o.cascadeSplits,
                               "given split distances (view depth, world units): cascades-1 "
                               "increasing values")
                    ->delimiter(',')
                    ->excludes(lambda));
  tunesCascades(app.add_option("--cascade-fit", o.cascadeFit,
                               "stabilized (bounding sphere, texel snapping) or tight (shimmers)")
                    ->capture_default_str());
  tunesCascades(app.add_option("--cascade-depth", o.cascadeDepth,
                               "fixed (near plane .. shadow distance) or fitted (visible depth "
                               "range, GPU reduction)")
                    ->capture_default_str());
  tunesCascades(app.add_option("--cascade-blend", o.cascadeBlend,
                               "share of each cascade blended into the next, 0..0.5")
                    ->capture_default_str());
  tunesCascades(
      app.add_option("--shadow-distance", o.shadowDistance,
                     "where cascaded shadows end, [0, 1e6] world units (0: the far side of the "
                     "scene, in whole diameters)")
          ->capture_default_str());
  app.add_option("--overlay", o.overlay, "none or cascades (tint pixels by cascade)")
      ->capture_default_str();
}

RenderOptions measurementRenderDefaults() {
  RenderOptions o;
  o.shadowSize = 1024;
  o.blurKernel = "box";
  o.filter = "bilinear";
  o.width = 480;
  o.height = 270;
  return o;
}

gl::RenderSettings renderSettingsOf(const RenderOptions& o) {
  gl::RenderSettings s;
  s.shadowMapSize = o.shadowSize;
  s.msaaSamples = o.msaa;
  s.blur.radius = gl::blurRadiusOfTaps(o.blurTaps);
  s.blur.kernel = gl::parseBlurKernel(o.blurKernel);
  s.blur.sigma =
      o.blurSigma ? gl::checkedBlurSigma(*o.blurSigma) : gl::defaultBlurSigma(s.blur.radius);
  s.filter = parseFilterMode(o.filter);
  s.anisotropy = o.aniso;
  s.width = o.width;
  s.height = o.height;
  s.normalOffsetTexels = o.normalOffset;
  s.cascades.count = o.cascades;
  s.cascades.lambda = o.cascadeLambda;
  s.cascades.distances = o.cascadeSplits;
  s.cascades.fit = parseCascadeFit(o.cascadeFit);
  s.cascades.fitDepthBounds = gl::parseCascadeDepth(o.cascadeDepth);
  s.cascades.blendBand = o.cascadeBlend;
  s.cascades.maxDistance = o.shadowDistance;
  s.overlay = gl::parseOverlay(o.overlay);
  return s;
}

void requireGivenOptionsApply(const RenderOptions& o, const gl::RenderSettings& s) {
  if (o.blurSigma && s.blur.kernel != BlurKernel::Gaussian) {
    throw Error("--blur-sigma sets the Gaussian blur's width, but the blur kernel is " +
                std::string(gl::blurKernelName(s.blur.kernel)) + ": give --blur-kernel gaussian");
  }
  if (o.cascadesTuned && s.cascades.count == 1) {
    throw Error(
        "the --cascade-* and --shadow-distance options tune cascaded shadow maps; give "
        "--cascades 2..8 (1 is one map of the whole scene)");
  }
}

gl::RenderSettings toRenderSettings(const RenderOptions& o) {
  gl::RenderSettings s = renderSettingsOf(o);
  requireGivenOptionsApply(o, s);
  gl::validateRenderSettings(s);
  return s;
}

}  // namespace penumbra::cli
