// The comparison report: per-technique images, error heat maps and crops, the grid,
// metrics.json and metrics.csv, plots, and a self-contained index.html.
#pragma once

#include <filesystem>
#include <vector>

#include "penumbra/compare/comparison.h"

namespace penumbra::compare {

// Writes the report's files into the existing folder `dir` (a ReportFolder's staging folder,
// report_folder.h); throws Error when a file cannot be written.
// The report's ranking: the techniques by RMSE against the ray-traced truth where there is one,
// else against the filtered (or area-light) reference, best first, ties in the request's order; a technique whose error is NaN (a visibility that is
// not a number, VisibilityErrors::nonFinitePixels) ranks last.
std::vector<const TechniqueResult*> rankTechniques(const ComparisonResult& result);

void writeReportFiles(const ComparisonResult& result, const std::filesystem::path& dir);

}  // namespace penumbra::compare
