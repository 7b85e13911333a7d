// The accuracy gate: every technique on every built-in scene against the filtered reference at
// small sizes, each RMSE held to a ceiling from one table (docs/results/accuracy-ceilings.csv),
// so that CI fails the day a technique breaks on any scene. `penumbra accuracy` measures and
// checks the matrix; tests/gl/accuracy_gate_test.cpp runs it in CI.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/compare/comparison.h"

namespace penumbra::compare {

// The gate's comparison of one scene: every technique, 256^2 shadow map, 5-tap box blur,
// bilinear lookups, 160x90, two camera-path frames, no ground-truth supersampling — the README's
// defaults scaled down for llvmpipe.
ComparisonRequest accuracyRequest(std::string_view scene);

// A setting the gate checks beyond its defaults, on one scene: "default" runs every built-in
// scene; "trilinear", "anisotropic", "sat" (summed-area tables, the techniques that allow them),
// "gaussian" (5-tap Gaussian blur, sigma 1), "cascades" (three) and "msaa" (4 samples) run one
// scene each, at the default's sizes.
struct AccuracyConfiguration {
  std::string name;
  std::string scene;  // empty: every built-in scene
};
std::vector<AccuracyConfiguration> accuracyConfigurations();
// The comparison of `scene` under a configuration; its techniques are those the renderer
// accepts under it.
ComparisonRequest accuracyRequest(const AccuracyConfiguration& configuration,
                                  std::string_view scene, const gl::Renderer& renderer);

struct AccuracyEntry {
  std::string configuration;  // AccuracyConfiguration::name
  std::string scene;
  std::string technique;  // technique id
  double rmse = 0.0;      // against the filtered reference, frame 0
};

// Measures every configuration: the default over every built-in scene (scenes x techniques,
// scene order first), then each other configuration's scene.
std::vector<AccuracyEntry> measureAccuracy(gl::Renderer& renderer, const Progress& progress = {});

struct AccuracyCeiling {
  std::string configuration;
  std::string scene;
  std::string technique;
  double measured = 0.0;  // when the ceiling was set (docs/results/accuracy.md names the machine)
  double ceiling = 0.0;
};

// The ceilings table: CSV with a header
// `configuration,scene,technique,measured_rmse,ceiling_rmse`; throws
// Error naming the file and line of a malformed row.
std::vector<AccuracyCeiling> readAccuracyCeilings(const std::filesystem::path& csv);
// Ceilings at `factor` times each measured RMSE, never below `floor` (for the exact ones).
std::vector<AccuracyCeiling> ceilingsFor(const std::vector<AccuracyEntry>& measured, double factor,
                                         double floor);
void writeAccuracyCeilings(const std::vector<AccuracyCeiling>& ceilings,
                           const std::filesystem::path& csv);

// One line per entry that breaks its ceiling or has none, and per ceiling without a
// measurement; empty when the gate passes.
std::vector<std::string> checkAccuracy(const std::vector<AccuracyEntry>& measured,
                                       const std::vector<AccuracyCeiling>& ceilings);

}  // namespace penumbra::compare
