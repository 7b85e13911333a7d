// The comparison report: per-technique images, error heat maps and crops, the grid,
// metrics.json and metrics.csv, plots, and a self-contained index.html.
#pragma once

#include <filesystem>

#include "penumbra/compare/comparison.h"

namespace penumbra::compare {

// Creates `outDir`'s staging folder (a sibling named outDir + ".partial"); throws Error when the
// location is not writable. Call before the long run, so bad output paths fail fast.
std::filesystem::path prepareReportFolder(const std::filesystem::path& outDir);

// Writes the report into the staging folder and renames it to `outDir` (replacing an earlier
// report) only once complete; on failure the staging folder is removed and nothing that looks
// like a finished report is left.
void writeReport(const ComparisonResult& result, const std::filesystem::path& staging,
                 const std::filesystem::path& outDir);

}  // namespace penumbra::compare
