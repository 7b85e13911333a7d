// `penumbra bench`: the seed papers' performance experiments rerun with penumbra, as ratios
// measured side by side in one run (warm-up, repeats, medians and spread), each beside the
// paper's own figure. Absolute times on the papers' GPUs (GeForce 8800 GTX, GTX 280) say nothing of
// ours; the ratios between techniques, and how cost grows with the kernel, are what can be
// compared.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "penumbra/gl/renderer.h"

namespace penumbra::compare {

// One configuration of an experiment.
struct BenchCase {
  std::string label;   // "ESM (threshold), 7x7"
  std::string series;  // the curve or table column it belongs to: "ESM (threshold)"
  double x = 0.0;      // the swept quantity (kernel width, layers), 0 where none
  gl::RenderSettings settings;
  // The paper's value of this case's time relative to the experiment's baseline (and of its
  // memory, where the paper gives one), with where it comes from.
  std::optional<double> paperTimeRatio;
  std::optional<double> paperMemoryRatio;
  std::string paperNote;
};

struct Experiment {
  std::string id;      // "esm-table1"
  std::string title;   // "ESM paper, Table 1: ESM, VSM and CSM at 2048²"
  std::string claim;   // what the paper showed, in a sentence
  std::string xLabel;  // the swept quantity's name, empty where the cases are a table
  std::vector<BenchCase> cases;
  // Each case's ratios are against the case of this series with the same x (or the only one).
  std::string baselineSeries;
  // Fit each series' growth with x (time above its x = 1 case against x, log-log): the
  // kernel-scaling claim.
  bool fitsExponents = false;
};

// The sizes the experiments run at: the papers' 2048² maps by default, smaller for tests.
struct BenchSizes {
  int shadowMapSize = 2048;
  int width = 960;
  int height = 540;
  int scalingShadowMapSize = 1024;  // kernel-scaling runs 31x31 PCF: kept smaller on llvmpipe
};

// The papers' "k x k Gauss filter" as penumbra's prefilter: radius (k - 1)/2, sigma a quarter of
// the width (at least half a texel); k = 1 is no filter. Shared by the bench and the figures.
BlurSpec paperGaussFilter(int k);

// The experiments' ids in the order they run.
std::vector<std::string> paperExperimentIds();
// Throws Error for an unknown id, listing the valid ones.
Experiment makePaperExperiment(const std::string& id, const BenchSizes& sizes);

struct CaseMeasurement {
  BenchCase benchCase;
  std::vector<double> frameMs;  // each timed frame's shadow cost: every pass of the frame
  double medianMs = 0.0;
  double minMs = 0.0;
  double maxMs = 0.0;
  gl::PassTimes medianPasses;  // per pass, medians over the timed frames
  uint64_t shadowBytes = 0;    // channel texture, summed-area table and auxiliary (no scratch);
                               // PCF, the hard test: the light pass's R32F depth
  double timeRatio = 0.0;      // median over the baseline's median
  double memoryRatio = 0.0;
};

struct ExperimentResult {
  Experiment experiment;
  std::vector<CaseMeasurement> cases;
  std::string timing;  // "GPU timer queries" or "wall clock (glFinish around each pass)"
  std::vector<std::string> findings;  // the fitted exponents, in words
};

// Renders every case of the experiment on `scene` (one warm-up frame, then `repeats` timed
// frames). GPU timer queries where they measure execution, wall clock on software rasterisers.
ExperimentResult runPaperExperiment(gl::Renderer& renderer, const Scene& scene,
                                    const Experiment& experiment, int repeats);

// time = offset + scale k^exponent, least squares over a series, the exponent to 0.001 in
// [0, 4], for the kernel-scaling claim (PCF k², separable blur k, summed-area table flat). The
// offset holds a pass's fixed cost, which would otherwise read as slower growth. Throws Error for
// fewer than three pairs, fewer than two distinct kernels, non-positive kernels, or non-finite
// times.
struct PowerLawFit {
  double offset = 0.0, scale = 0.0, exponent = 0.0;
};
PowerLawFit fitPowerLaw(const std::vector<double>& k, const std::vector<double>& ms);

}  // namespace penumbra::compare
