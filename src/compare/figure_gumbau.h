// Gumbau et al. Fig. 3: the power-function CDF against VSM and ESM on the spheres scene, with
// the anatomy of the power CDF's leaking pixels.
#pragma once

#include <filesystem>

#include "penumbra/compare/paper_figures.h"
#include "penumbra/gl/renderer.h"

namespace penumbra::compare {

FigureItem gumbauFigure3(gl::Renderer& renderer, const FiguresOptions& o,
                         const std::filesystem::path& dir);

}  // namespace penumbra::compare
