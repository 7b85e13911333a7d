// The comparison report: per-technique images, error heat maps and crops, the grid,
// metrics.json and metrics.csv, plots, and a self-contained index.html.
#pragma once

#include <filesystem>

#include "penumbra/compare/comparison.h"

namespace penumbra::compare {

// Writes the report's files into the existing folder `dir` (a ReportFolder's staging folder,
// report_folder.h); throws Error when a file cannot be written.
void writeReportFiles(const ComparisonResult& result, const std::filesystem::path& dir);

}  // namespace penumbra::compare
