// `penumbra bench`'s outputs: bench.json, bench.csv and index.html (with gnuplot plots) in a
// folder, each measured ratio beside the paper's.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/compare/paper_bench.h"

namespace penumbra::compare {

struct PaperBenchContext {
  std::string device;
  std::string scene;
  int repeats = 0;
  std::string command;  // the command line that produced the results
};

// Writes into `dir` (created if missing); throws Error when a file cannot be written or gnuplot
// fails.
void writePaperBenchReport(const std::vector<ExperimentResult>& results,
                           const PaperBenchContext& context, const std::filesystem::path& dir);

}  // namespace penumbra::compare
