// The frontier and its plot (frontier.h).
#include "frontier.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gnuplot.h"

namespace penumbra::tune {

std::vector<CostPoint> paretoFront(std::vector<CostPoint> points) {
  std::stable_sort(points.begin(), points.end(), [](const CostPoint& a, const CostPoint& b) {
    return a.cost < b.cost || (a.cost == b.cost && a.error < b.error);
  });
  std::vector<CostPoint> front;
  for (const CostPoint& p : points) {
    if (front.empty() || p.error < front.back().error) front.push_back(p);
  }
  return front;
}

void plotFrontier(const std::vector<CostPoint>& points, const std::vector<std::string>& techniques,
                  const std::string& costLabel, const std::string& errorLabel,
                  const std::string& title, const std::filesystem::path& png) {
  GnuplotRun gnuplot(png.parent_path());
  const std::filesystem::path data = gnuplot.scratchFile("points.dat");
  const std::filesystem::path frontData = gnuplot.scratchFile("front.dat");
  {
    std::ofstream out(data), front(frontData);
    // One block per technique (two blank lines apart), so gnuplot's `index` colours each.
    for (const std::string& t : techniques) {
      out << "# " << t << "\n";
      bool any = false;
      for (const CostPoint& p : points) {
        if (p.technique != t) continue;
        out << std::max(p.cost, 1e-3) << " " << std::max(p.error, 1e-6) << "\n";
        any = true;
      }
      if (!any) out << "nan nan\n";  // keeps the block, so indices stay the techniques'
      out << "\n\n";
    }
    for (const CostPoint& p : paretoFront(points)) {
      front << std::max(p.cost, 1e-3) << " " << std::max(p.error, 1e-6) << " \"" << p.technique
            << "\"\n";
    }
    if (!out || !front) throw Error("cannot write the data of " + png.string());
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo size 760,500 font 'DejaVu Sans,10'\n"
     << "set output " << gnuplotOutput(png) << "\n"
     << "set title " << gnuplotText(title) << " noenhanced\n"
     << "set xlabel " << gnuplotText(costLabel) << " noenhanced\n"
     << "set ylabel " << gnuplotText(errorLabel) << " noenhanced\n"
     // Both axes logarithmic: costs span decades, and so do errors (a tuned setting may cut
     // the default's several times, an outlier may be ten times worse than either).
     << "set grid\nset key outside right top\nset logscale xy\n"
     << "set offsets graph 0.02, graph 0.1, graph 0.1, graph 0.05\n"
     << "plot ";
  for (size_t i = 0; i < techniques.size(); ++i) {
    gp << gnuplotPath(data) << " index " << i << " using 1:2 with points pt 7 ps 0.8 title "
       << gnuplotText(techniques[i]) << ", ";
  }
  gp << gnuplotPath(frontData)
     << " using 1:2 with steps lw 2 lc rgb '#222222' title 'frontier', "
     << "'' using 1:2:3 with labels offset 0,0.8 font ',8' notitle noenhanced\n";
  gnuplot.run(gp.str());
}

}  // namespace penumbra::tune
