// Helpers of the step-function figures (curve_figure_tools.h).
#include "curve_figure_tools.h"

#include <cmath>

#include "penumbra/error.h"

namespace penumbra::compare {

size_t curveColumn(const CurvesTable& t, const std::string& name) {
  for (size_t c = 0; c < t.columns.size(); ++c) {
    if (t.columns[c] == name) return c;
  }
  throw Error("no curve '" + name + "' in the table");
}

float curveValueAt(const CurvesTable& t, const std::string& name, float depth) {
  size_t best = 0;
  for (size_t i = 0; i < t.receiverDepths.size(); ++i) {
    if (std::abs(t.receiverDepths[i] - depth) < std::abs(t.receiverDepths[best] - depth)) best = i;
  }
  return t.values[curveColumn(t, name)][best];
}

CurvesTable plottedCurves(const CurvesRequest& request, const std::string& title,
                          const std::filesystem::path& dir, const std::string& name,
                          CurvesPlotRange range) {
  const CurvesTable table = computeCurves(request);
  const std::filesystem::path csv = dir / (name + ".csv");
  writeCurvesCsv(table, csv);
  plotCurves(csv, table, title, dir / (name + ".png"), range);
  return table;
}

StepCurve stepCurveOf(const CurvesTable& t, const std::string& name, float occluderDepth) {
  StepCurve c;
  c.v = t.values[curveColumn(t, name)];
  for (float d : t.receiverDepths) c.x.push_back(d - occluderDepth);
  return c;
}

}  // namespace penumbra::compare
