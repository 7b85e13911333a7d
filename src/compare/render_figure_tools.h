// What the rendered figures share: variants of a technique, each measured on one scene against
// the filtered reference with compare's machinery (comparison.h) and shown as its shaded image
// and error heat map, and the table of their errors.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/compare/comparison.h"
#include "penumbra/compare/paper_figures.h"
#include "penumbra/gl/renderer.h"

namespace penumbra::compare {

gl::RenderSettings figureSettings(const FiguresOptions& o);

// One variant of a figure: a technique with its own parameters, measured on `scene`.
struct Variant {
  std::string label;
  Technique technique;
  std::vector<const char*> params;  // NAME=VALUE on top of the defaults
};

struct VariantResult {
  Variant variant;
  TechniqueResult result;
};

// Renders each variant beside the filtered reference and writes its shaded image and error
// heat map into dir/renders as <figure>_<variant>.png and ..._error.png, adding both to `images`.
std::vector<VariantResult> measureVariants(gl::Renderer& renderer, const FiguresOptions& o,
                                           const std::string& figure, const std::string& scene,
                                           const std::vector<Variant>& variants,
                                           const std::filesystem::path& dir,
                                           std::vector<std::string>& images);

// The variants' RMSE, leaking and over-darkened shares and largest error, as an HTML table.
std::string errorsTable(const std::vector<VariantResult>& results);

// A share as a percentage with two decimals.
std::string percent(double share);

}  // namespace penumbra::compare
