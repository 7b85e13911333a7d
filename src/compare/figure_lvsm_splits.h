// Thesis Fig. 4.2: LVSM with uniform against Lloyd-placed splits on the bench scene, and why the
// uniform splits leak (the depths that share a layer).
#pragma once

#include <filesystem>

#include "penumbra/compare/paper_figures.h"
#include "penumbra/gl/renderer.h"

namespace penumbra::compare {

FigureItem lvsmFigure42(gl::Renderer& renderer, const FiguresOptions& o,
                        const std::filesystem::path& dir);

}  // namespace penumbra::compare
