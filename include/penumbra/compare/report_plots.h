// gnuplot figures of the report: error heat maps, the image grid, error-vs-cost scatter plots.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/gnuplot.h"
#include "penumbra/image.h"

namespace penumbra::compare {

// Each figure is queued into a GnuplotRun and drawn when the run runs: a report draws all its
// figures in one batch (GnuplotRun::run). The heat map's overload without a run draws at once.

// A diverging heat map of signed error (blue: over-darkening, red: light leaking) with its
// colour bar, over [-range, range].
void plotErrorHeatMap(GnuplotRun& gnuplot, const Image& error, double range,
                      const std::string& title, const std::filesystem::path& png);
void plotErrorHeatMap(const Image& error, double range, const std::string& title,
                      const std::filesystem::path& png);

struct GridTile {
  std::filesystem::path png;  // an existing PNG
  std::string title;
};
void plotImageGrid(GnuplotRun& gnuplot, const std::vector<GridTile>& tiles, int columns,
                   int tileWidth, int tileHeight, const std::filesystem::path& png);

struct ScatterPoint {
  std::string label;
  double x;
  double y;
};
// Labelled points with the Pareto front (lower x and lower y are better) drawn as a line.
void plotParetoScatter(GnuplotRun& gnuplot, const std::vector<ScatterPoint>& points,
                       const std::string& xLabel, const std::string& yLabel,
                       const std::string& title, bool logX,
                       const std::filesystem::path& png);

}  // namespace penumbra::compare
