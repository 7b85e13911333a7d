// The frontier and its plot (frontier.h).
#include "frontier.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gnuplot.h"

namespace penumbra::tune {

namespace {

// gnuplot's tic list of the 1, 2, 5 x 10^k values in [lo, hi].
std::string oneTwoFiveTics(double lo, double hi) {
  std::ostringstream tics;
  tics << "(";
  bool first = true;
  for (int k = int(std::floor(std::log10(lo))); k <= int(std::ceil(std::log10(hi))); ++k) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, k);
      if (v < lo || v > hi) continue;
      tics << (first ? "" : ", ") << "'" << v << "' " << v;
      first = false;
    }
  }
  tics << ")";
  return tics.str();
}

}  // namespace

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
    // Labelled where the frontier's technique changes: one name per stretch, not per point.
    std::string previous;
    for (const CostPoint& p : paretoFront(points)) {
      front << std::max(p.cost, 1e-3) << " " << std::max(p.error, 1e-6) << " \""
            << (p.technique != previous ? p.technique : "") << "\"\n";
      previous = p.technique;
    }
    if (!out || !front) throw Error("cannot write the data of " + png.string());
  }
  // The axes hug the data (log autoscaling would pad to whole decades).
  double minCost = INFINITY, maxCost = 0.0, minError = INFINITY, maxError = 0.0;
  for (const CostPoint& p : points) {
    minCost = std::min(minCost, std::max(p.cost, 1e-3));
    maxCost = std::max(maxCost, std::max(p.cost, 1e-3));
    minError = std::min(minError, std::max(p.error, 1e-6));
    maxError = std::max(maxError, std::max(p.error, 1e-6));
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
     << "set xrange [" << minCost / 1.3 << ":" << maxCost * 1.3 << "]\n"
     << "set yrange [" << minError / 1.3 << ":" << maxError * 1.3 << "]\n"
     // Errors and costs span a decade or two: 1-2-5 tics, where gnuplot's log axes label
     // decades only.
     << "set xtics " << oneTwoFiveTics(minCost / 1.3, maxCost * 1.3) << "\n"
     << "set ytics " << oneTwoFiveTics(minError / 1.3, maxError * 1.3) << "\n"
     << "plot ";
  // Ten colours that stay apart (gnuplot's own cycle repeats after eight), then point shapes.
  static constexpr const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                             "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                             "#bcbd22", "#17becf"};
  for (size_t i = 0; i < techniques.size(); ++i) {
    gp << gnuplotPath(data) << " index " << i << " using 1:2 with points pt " << (7 + 2 * (i / 10))
       << " ps 0.8 lc rgb '" << kColours[i % 10] << "' title " << gnuplotText(techniques[i])
       << ", ";
  }
  gp << gnuplotPath(frontData)
     << " using 1:2 with steps lw 2 lc rgb '#222222' title 'frontier', "
     << "'' using 1:2:3 with labels offset 0,0.8 font ',8' notitle noenhanced\n";
  gnuplot.run(gp.str());
}

}  // namespace penumbra::tune
