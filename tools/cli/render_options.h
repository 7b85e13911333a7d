// Command-line options shared by the subcommands that render (render, compare): shadow-map size,
// MSAA, prefilter, filter mode, anisotropy, frame size, normal offset, cascades, overlay.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/gl/renderer.h"

namespace penumbra::cli {

struct RenderOptions {
  int shadowSize = 2048;
  int msaa = 1;
  int blurTaps = 5;
  std::string blurKernel = "gaussian";
  std::optional<float> blurSigma;  // unset: gl::defaultBlurSigma of the radius
  std::string filter = "trilinear";
  int aniso = 16;
  int width = 960;
  int height = 540;
  float normalOffset = 0.0f;
  int cascades = 1;
  float cascadeLambda = 0.5f;
  std::vector<float> cascadeSplits;
  std::string cascadeFit = "stabilized";
  bool cascadesTuned = false;  // a --cascade-* or --shadow-distance option was given
  std::string cascadeDepth = "fixed";
  float cascadeBlend = 0.1f;
  float shadowDistance = 0.0f;
  std::string overlay = "none";
};

// The defaults of the subcommands that measure (compare, tune): sized for a two-core machine
// without a GPU (compare's whole report in about 20 s): 1024² maps, a box blur, bilinear
// lookups, 480x270 frames.
RenderOptions measurementRenderDefaults();

// Adds the options with `defaults` as their defaults.
void addRenderOptions(CLI::App& app, RenderOptions& options);

// Renderer settings from the options (technique and parameters left at their defaults), names
// and widths turned into values (penumbra/gl/render_setting_values.h) but ranges not checked yet:
// a settings file merged in later may supply what they need (the cascade count). Throws Error for
// an unknown name or an even blur width.
gl::RenderSettings renderSettingsOf(const RenderOptions& options);
// Throws Error when an option given would be ignored by `settings`, what the command renders
// with (a settings file merged in): a --cascade-* or --shadow-distance option with one cascade,
// --blur-sigma with a box kernel.
void requireGivenOptionsApply(const RenderOptions& options, const gl::RenderSettings& settings);
// renderSettingsOf, checked (requireGivenOptionsApply, gl::validateRenderSettings): for commands
// without a settings file.
gl::RenderSettings toRenderSettings(const RenderOptions& options);

}  // namespace penumbra::cli
