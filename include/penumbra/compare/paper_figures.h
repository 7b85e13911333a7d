// `penumbra figures`: the seed papers' figures and tables regenerated with penumbra into one HTML
// page, each item beside a caption saying what the paper showed, what we measured and whether
// the two agree (and why not, where they do not).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "penumbra/compare/paper_bench.h"
#include "penumbra/gl/renderer.h"

namespace penumbra::compare {

struct FiguresOptions {
  // Rendered figures: shadow-map and frame sizes (small defaults: the page must finish in
  // minutes on two CPU cores without a GPU; flags raise them).
  int shadowMapSize = 1024;
  int width = 960;
  int height = 540;
  // The bench tables: their sizes and timed frames per case.
  BenchSizes benchSizes{1024, 960, 540, 1024};
  int benchRepeats = 3;
  std::string command;  // the command line, printed on the page
};

// One item of the page: an id (its anchor), a title, the paper's finding, ours, the verdict,
// and the files (relative to the page) that show it.
struct FigureItem {
  std::string id;
  std::string title;
  std::string paper;     // what the paper showed
  std::string measured;  // what penumbra measured, with the numbers
  bool agrees = true;
  std::string verdict;  // agreement, or the disagreement and why
  std::vector<std::string> images;
  std::string tableHtml;  // a table of numbers, where the item is one
};

using FiguresProgress = std::function<void(const std::string& step)>;

// The step-function curves: ESM Fig. 2(a) and 2(b), CSM Fig. 3(a)-(d) one panel each, and the
// thesis's light-bleeding case (Fig. 3.4/3.5). Writes its plots into dir/curves.
std::vector<FigureItem> curveFigures(const std::filesystem::path& dir);

// The rendered figures and tables: ESM Table 3 and Fig. 1, CSM Fig. 6, thesis Fig. 4.2 and
// 4.7/4.8, Gumbau Fig. 3. Writes images into dir/renders.
std::vector<FigureItem> renderedFigures(gl::Renderer& renderer, const FiguresOptions& options,
                                        const std::filesystem::path& dir,
                                        const FiguresProgress& progress);

// Every item, the bench tables included (dir/bench), and dir/index.html.
void writePaperFigures(gl::Renderer& renderer, const FiguresOptions& options,
                       const std::filesystem::path& dir, const FiguresProgress& progress = {});

}  // namespace penumbra::compare
