// Command-line options shared by the subcommands that render (render, compare): shadow-map size,
// MSAA, prefilter, filter mode, anisotropy, frame size, normal offset, cascades, overlay.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "penumbra/gl/renderer.h"

namespace penumbra::cli {

struct RenderOptions {
  int shadowSize = 2048;
  int msaa = 1;
  int blurTaps = 5;
  std::string blurKernel = "gaussian";
  float blurSigma = 0.0f;  // 0: half the radius, at least 0.5
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

// Adds the options with `defaults` as their defaults.
void addRenderOptions(CLI::App& app, RenderOptions& options);

// Renderer settings from the options (technique and parameters left at their defaults);
// throws Error for an even blur width or an unknown kernel or filter.
gl::RenderSettings toRenderSettings(const RenderOptions& options);

}  // namespace penumbra::cli
