// CSM paper Fig. 3(a)-(d): the Fourier reconstruction of the shadow test and the four trade-offs
// it shows, one page item per panel, each with its own plot, measure and verdict.
#pragma once

#include <filesystem>
#include <vector>

#include "penumbra/compare/paper_figures.h"

namespace penumbra::compare {

// Writes the panels' plots into dir (csm_fig3a.png ... csm_fig3d.png, with their CSVs).
std::vector<FigureItem> csmFigure3Panels(const std::filesystem::path& dir);

}  // namespace penumbra::compare
