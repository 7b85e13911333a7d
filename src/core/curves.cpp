// Shadow-test curves over receiver depth for one filter-region depth distribution.
#include "penumbra/curves.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gnuplot.h"
#include "penumbra/output_journal.h"
#include "penumbra/params.h"

namespace penumbra {

CurvesTable computeCurves(const CurvesRequest& request) {
  if (request.samples < 2 || request.samples > 100000) {
    throw Error("curve samples " + std::to_string(request.samples) + " out of range [2, 100000]");
  }
  if (request.techniques.empty()) throw Error("no technique selected for the curves");
  for (Technique t : request.techniques) validateParams(t, request.params);

  CurvesTable table;
  table.columns.push_back("exact");
  for (Technique t : request.techniques) table.columns.emplace_back(techniqueId(t));
  table.values.resize(table.columns.size());
  for (int i = 0; i < request.samples; ++i) {
    const float receiver = float(i) / float(request.samples - 1);
    const std::vector<DepthSample> region = regionWithReceiver(request.occluders, receiver);
    table.receiverDepths.push_back(receiver);
    table.values[0].push_back(exactVisibility(region, receiver));
    for (size_t k = 0; k < request.techniques.size(); ++k) {
      const float v = evaluateOnRegion(request.techniques[k], request.params, region, receiver);
      if (!std::isfinite(v)) {
        throw Error(std::string(techniqueId(request.techniques[k])) +
                    " produced a non-finite visibility at receiver depth " +
                    std::to_string(receiver));
      }
      table.values[k + 1].push_back(v);
    }
  }
  return table;
}

void writeCurvesCsv(const CurvesTable& table, const std::filesystem::path& path) {
  // The header is split at commas (gnuplot's columnheader, any CSV reader): a comma in a name
  // would shift every later title onto the wrong curve.
  for (const std::string& c : table.columns) {
    if (c.find(',') != std::string::npos) throw Error("curve name '" + c + "' holds a comma");
  }
  recordOutput(path);
  std::ofstream out(path);
  if (!out) throw Error("cannot write " + path.string());
  out << "receiver_depth";
  for (const std::string& c : table.columns) out << "," << c;
  out << "\n" << std::setprecision(7);
  for (size_t i = 0; i < table.receiverDepths.size(); ++i) {
    out << table.receiverDepths[i];
    for (const std::vector<float>& column : table.values) out << "," << column[i];
    out << "\n";
  }
  if (!out) throw Error("failed while writing " + path.string());
}

void plotCurves(const std::filesystem::path& csvPath, const CurvesTable& table,
                const std::string& title, const std::filesystem::path& pngPath,
                CurvesPlotRange range) {
  GnuplotRun gnuplot(pngPath.parent_path());
  plotCurves(gnuplot, csvPath, table, title, pngPath, range);
  gnuplot.run();
}

void plotCurves(GnuplotRun& gnuplot, const std::filesystem::path& csvPath, const CurvesTable& table,
                const std::string& title, const std::filesystem::path& pngPath,
                CurvesPlotRange range) {
  if (!(range.from >= 0.0f && range.from < range.to && range.to <= 1.0f)) {
    throw Error("curve plot range [" + std::to_string(range.from) + ", " +
                std::to_string(range.to) + "] is not a window of [0, 1]");
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1200,750 enhanced font 'DejaVu Sans,11'\n"
     << "set output " << gnuplotOutput(pngPath) << "\n"
     << "set datafile separator ','\n"
     << "set title " << gnuplotText(title) << " noenhanced\n"
     << "set xlabel 'receiver depth d (linear light-space depth)'\n"
     << "set ylabel 'visibility'\n"
     << "set xrange [" << range.from << ":" << range.to << "]\nset yrange [-0.05:1.05]\n"
     << "set key outside right top noenhanced\nset grid\n"
     // Eleven distinguishable colours (Tableau-like) so no two techniques share one.
     << "set linetype 1 lc rgb '#1f77b4'\nset linetype 2 lc rgb '#ff7f0e'\n"
     << "set linetype 3 lc rgb '#2ca02c'\nset linetype 4 lc rgb '#d62728'\n"
     << "set linetype 5 lc rgb '#9467bd'\nset linetype 6 lc rgb '#8c564b'\n"
     << "set linetype 7 lc rgb '#e377c2'\nset linetype 8 lc rgb '#7f7f7f'\n"
     << "set linetype 9 lc rgb '#bcbd22'\nset linetype 10 lc rgb '#17becf'\n"
     << "set linetype 11 lc rgb '#000080'\nset linetype cycle 11\n"
     << "plot " << gnuplotPath(csvPath)
     << " using 1:2 with lines lw 3 lc rgb 'black' dt 2 title columnheader(2)";
  for (size_t c = 1; c < table.columns.size(); ++c) {
    gp << ", '' using 1:" << c + 2 << " with lines lt " << c << " lw 2 title columnheader(" << c + 2
       << ")";
  }
  gp << "\n";
  gnuplot.add(gp.str(), 1200.0 * 750.0);
}

}  // namespace penumbra
