// Shadow-test curves: every technique's visibility against receiver depth for one depth
// distribution inside a filter region, next to the exact filtered step (as ESM Fig. 2,
// CSM Fig. 3 and thesis Fig. 3.4 plot them).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/depth_distribution.h"
#include "penumbra/technique.h"

namespace penumbra {

struct CurvesRequest {
  std::vector<DepthSample> occluders;  // the planar receiver fills the rest of the region
  std::vector<Technique> techniques;
  TechniqueParams params = defaultTechniqueParams();
  int samples = 1001;  // receiver depths evenly over [0,1], in [2, 100000]
};

struct CurvesTable {
  std::vector<float> receiverDepths;
  std::vector<std::string> columns;        // "exact", then technique ids
  std::vector<std::vector<float>> values;  // values[column][sample]
};

// Validates the request (throws Error) and evaluates every column; every value is finite.
CurvesTable computeCurves(const CurvesRequest& request);

// CSV: header "receiver_depth,exact,<ids...>", one row per receiver depth.
void writeCurvesCsv(const CurvesTable& table, const std::filesystem::path& path);

// A PNG plot of the CSV through gnuplot; throws Error when gnuplot is missing or fails.
void plotCurves(const std::filesystem::path& csvPath, const CurvesTable& table,
                const std::string& title, const std::filesystem::path& pngPath);

}  // namespace penumbra
