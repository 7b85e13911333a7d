// gnuplot figures.
#include "penumbra/compare/report_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "penumbra/diagnostic_images.h"
#include "penumbra/error.h"
#include "penumbra/gnuplot.h"

namespace penumbra::compare {
namespace {

// The heat-map palette the viewer also draws with (penumbra/diagnostic_images.h), in gnuplot's
// syntax: -1 '#2166ac', ..., 1 '#b2182b'.
std::string gnuplotPalette() {
  std::string stops;
  for (const ErrorPaletteStop& s : errorPalette()) {
    char stop[32];
    std::snprintf(stop, sizeof stop, "%s%g '#%02x%02x%02x'", stops.empty() ? "" : ", ",
                  double(s.position), s.red, s.green, s.blue);
    stops += stop;
  }
  return stops;
}

}  // namespace

void plotErrorHeatMap(GnuplotRun& gnuplot, const Image& error, double range,
                      const std::string& title, const std::filesystem::path& png) {
  const std::filesystem::path data =
      gnuplot.scratchFile("error-" + std::to_string(gnuplot.figureCount()) + ".bin");
  {
    std::ofstream out(data, std::ios::binary);
    out.write(reinterpret_cast<const char*>(error.data().data()),
              std::streamsize(error.data().size() * sizeof(float)));
    if (!out) throw Error("cannot write " + data.string());
  }
  std::ostringstream gp;
  // Room for the colour bar and its label whatever the image size.
  const int width = error.width() + 240, height = std::max(error.height() + 80, 340);
  gp << "set terminal pngcairo size " << width << "," << height << " font 'DejaVu Sans,10'\n"
     << "set output " << gnuplotOutput(png) << "\n"
     << "set title " << gnuplotText(title) << " noenhanced\n"
     << "set palette defined (" << gnuplotPalette() << ")\n"
     << "set cbrange [" << -range << ":" << range << "]\n"
     << "set cblabel 'red: leaks light   blue: over-darkens'\n"
     << "unset xtics\nunset ytics\nset size ratio -1\n"
     << "set xrange [-0.5:" << error.width() - 0.5 << "]\nset yrange [-0.5:" << error.height() - 0.5
     << "]\n"
     << "plot " << gnuplotPath(data) << " binary array=(" << error.width() << "," << error.height()
     << ") format='%float' flipy with image notitle\n";
  gnuplot.add(gp.str(), double(width) * height);
}

void plotErrorHeatMap(const Image& error, double range, const std::string& title,
                      const std::filesystem::path& png) {
  GnuplotRun gnuplot(png.parent_path());
  plotErrorHeatMap(gnuplot, error, range, title, png);
  gnuplot.run();
}

void plotImageGrid(GnuplotRun& gnuplot, const std::vector<GridTile>& tiles, int columns,
                   int tileWidth, int tileHeight, const std::filesystem::path& png) {
  const int rows = (int(tiles.size()) + columns - 1) / columns;
  const int width = columns * tileWidth, height = rows * (tileHeight + 30);
  std::ostringstream gp;
  gp << "set terminal pngcairo size " << width << "," << height << " font 'DejaVu Sans,11'\n"
     << "set output " << gnuplotOutput(png) << "\n"
     << "set multiplot layout " << rows << "," << columns << "\n"
     << "unset key\nunset tics\nunset border\nset size ratio -1\n"
     << "set lmargin 0.5\nset rmargin 0.5\nset bmargin 0.5\nset tmargin 1.8\n";
  for (const GridTile& t : tiles) {
    gp << "set title " << gnuplotText(t.title) << " noenhanced\n"
       << "plot " << gnuplotPath(t.png) << " binary filetype=png with rgbimage\n";
  }
  gp << "unset multiplot\n";
  gnuplot.add(gp.str(), double(width) * height);
}

void plotParetoScatter(GnuplotRun& gnuplot, const std::vector<ScatterPoint>& points,
                       const std::string& xLabel, const std::string& yLabel,
                       const std::string& title, bool logX, const std::filesystem::path& png) {
  const std::string figure = std::to_string(gnuplot.figureCount());
  const std::filesystem::path data = gnuplot.scratchFile("points-" + figure + ".dat");
  const std::filesystem::path front = gnuplot.scratchFile("front-" + figure + ".dat");
  std::vector<ScatterPoint> sorted = points;
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  {
    std::ofstream out(data), pareto(front);
    double best = INFINITY;
    for (const ScatterPoint& p : sorted) {
      out << p.x << " " << p.y << " \"" << p.label << "\"\n";
      if (p.y < best) {
        pareto << p.x << " " << p.y << "\n";
        best = p.y;
      }
    }
    if (!out || !pareto) throw Error("cannot write the data of " + png.string());
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo size 720,480 font 'DejaVu Sans,10'\n"
     << "set output " << gnuplotOutput(png) << "\n"
     << "set title " << gnuplotText(title) << " noenhanced\n"
     << "set xlabel " << gnuplotText(xLabel) << " noenhanced\nset ylabel " << gnuplotText(yLabel)
     << " noenhanced\nset grid\nset key top right\nset offsets graph 0.05, graph 0.15, graph 0.1, "
        "graph 0.05\n"
     << (logX ? "set logscale x\n" : "") << "plot " << gnuplotPath(front)
     << " using 1:2 with linespoints lw 2 lc rgb '#b2182b' title 'Pareto front', "
     << gnuplotPath(data) << " using 1:2 with points pt 7 ps 1.3 lc rgb '#2166ac' notitle, "
     << "'' using 1:2:3 with labels offset 0,1 font ',9' notitle noenhanced\n";
  gnuplot.add(gp.str(), 720.0 * 480.0);
}

}  // namespace penumbra::compare
