// What the step-function figures share: a curve table computed, written as CSV and plotted, and
// a column read back as a step curve over d - z for the step-shape measures.
#pragma once

#include <filesystem>
#include <string>

#include "penumbra/curves.h"
#include "penumbra/step_shape.h"

namespace penumbra::compare {

size_t curveColumn(const CurvesTable& t, const std::string& name);

// The value of column `name` at the sample nearest `depth`.
float curveValueAt(const CurvesTable& t, const std::string& name, float depth);

// Computes the curves, writes dir/name.csv and plots dir/name.png over `range`.
CurvesTable plottedCurves(const CurvesRequest& request, const std::string& title,
                          const std::filesystem::path& dir, const std::string& name,
                          CurvesPlotRange range = {});

// Column `name` over x = d - occluderDepth, for a region that one occluder at occluderDepth
// fills (so the exact curve is the step H(occluderDepth - d)).
StepCurve stepCurveOf(const CurvesTable& t, const std::string& name, float occluderDepth);

}  // namespace penumbra::compare
