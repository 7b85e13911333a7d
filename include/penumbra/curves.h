// Shadow-test curves: every technique's visibility against receiver depth for one depth
// distribution inside a filter region, next to the exact filtered step (as ESM Fig. 2,
// CSM Fig. 3 and thesis Fig. 3.4 plot them).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/depth_distribution.h"
#include "penumbra/gnuplot.h"
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

// CSV: header "receiver_depth,exact,<ids...>", one row per receiver depth. Throws Error when a
// column name holds a comma (it would split the header).
void writeCurvesCsv(const CurvesTable& table, const std::filesystem::path& path);

// The receiver depths a plot shows: all of [0,1], or a window around a step (the papers zoom
// in on theirs: "the range has been scaled to emphasize the effects", CSM Fig. 3).
struct CurvesPlotRange {
  float from = 0.0f;  // in [0,1), below `to`
  float to = 1.0f;
};

// A PNG plot of the CSV through gnuplot; throws Error when gnuplot is missing or fails, or the
// range is empty or leaves [0,1].
void plotCurves(const std::filesystem::path& csvPath, const CurvesTable& table,
                const std::string& title, const std::filesystem::path& pngPath,
                CurvesPlotRange range = {});
// The same plot queued into `gnuplot`, drawn when it runs (gnuplot.h).
void plotCurves(GnuplotRun& gnuplot, const std::filesystem::path& csvPath,
                const CurvesTable& table, const std::string& title,
                const std::filesystem::path& pngPath, CurvesPlotRange range = {});

}  // namespace penumbra
