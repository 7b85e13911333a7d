// The accuracy gate: every technique on every built-in scene against the filtered reference, and
// on one scene each under the other lookups, a Gaussian blur, cascades and MSAA
// (compare::accuracyConfigurations), each RMSE under its ceiling in
// docs/results/accuracy-ceilings.csv (set at 1.25x the value
// measured on llvmpipe when the table was written; `penumbra accuracy --write-ceilings` rewrites
// it). CI fails the day a technique breaks on any scene.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>

#include "gl_test_context.h"
#include "penumbra/compare/accuracy.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

const std::filesystem::path kCeilings =
    std::filesystem::path(PENUMBRA_SOURCE_DIR) / "docs/results/accuracy-ceilings.csv";

class AccuracyGate : public testing::GlTest {};

TEST_F(AccuracyGate, EveryTechniqueOnEverySceneStaysUnderItsCeiling) {
  gl::Renderer renderer(*context);
  const std::vector<compare::AccuracyEntry> measured = compare::measureAccuracy(renderer);
  const std::vector<compare::AccuracyCeiling> ceilings = compare::readAccuracyCeilings(kCeilings);
  // The default configuration runs every technique on every scene; each other one at least the
  // techniques that allow summed-area tables (VSM, LVSM, CSM, MSM and the depth tests).
  size_t defaults = 0;
  std::set<std::string> configurations;
  for (const compare::AccuracyEntry& e : measured) {
    defaults += e.configuration == "default";
    configurations.insert(e.configuration);
  }
  EXPECT_EQ(defaults, builtinSceneNames().size() * allTechniques().size());
  EXPECT_EQ(configurations.size(), compare::accuracyConfigurations().size());
  for (const std::string& problem : compare::checkAccuracy(measured, ceilings)) {
    ADD_FAILURE() << problem;
  }
  // The ceilings were measured on llvmpipe: there, an entry that got much better must tighten its
  // ceiling (the table keeps 1.25x; more than another 1.25x of slack means a stale ceiling).
  if (renderer.deviceDescription().find("llvmpipe") == std::string::npos) return;
  for (const compare::AccuracyEntry& e : measured) {
    for (const compare::AccuracyCeiling& c : ceilings) {
      if (c.configuration != e.configuration || c.scene != e.scene || c.technique != e.technique ||
          c.ceiling <= 1e-6)
        continue;
      EXPECT_GE(e.rmse * 1.25 * 1.25, c.ceiling)
          << e.configuration << " " << e.scene << " " << e.technique << " improved to " << e.rmse
          << ": tighten its ceiling (penumbra accuracy --write-ceilings)";
    }
  }
}

TEST(AccuracyCheck, FlagsEntriesOverTheirCeilingMissingCeilingsAndStaleRows) {
  const std::vector<compare::AccuracyEntry> measured{{"default", "bench", "vsm", 0.05},
                                                     {"default", "bench", "esm", 0.2},
                                                     {"default", "planar", "msm", 0.01},
                                                     {"sat", "bench", "vsm", 0.05}};
  const std::vector<compare::AccuracyCeiling> ceilings{{"default", "bench", "vsm", 0.04, 0.05},
                                                       {"default", "bench", "esm", 0.1, 0.125},
                                                       {"default", "spheres", "csm", 0.1, 0.2},
                                                       {"sat", "bench", "vsm", 0.02, 0.025}};
  const std::vector<std::string> problems = compare::checkAccuracy(measured, ceilings);
  ASSERT_EQ(problems.size(), 4u);  // default vsm sits exactly on its ceiling: allowed
  EXPECT_NE(problems[0].find("default bench esm: RMSE 0.2 exceeds its ceiling 0.125"),
            std::string::npos)
      << problems[0];
  EXPECT_NE(problems[1].find("default planar msm: RMSE 0.01 has no ceiling"), std::string::npos)
      << problems[1];
  // The same scene and technique under another configuration has a ceiling of its own.
  EXPECT_NE(problems[2].find("sat bench vsm: RMSE 0.05 exceeds its ceiling 0.025"),
            std::string::npos)
      << problems[2];
  EXPECT_NE(problems[3].find("default spheres csm: a ceiling without a measurement"),
            std::string::npos)
      << problems[3];
}

TEST(AccuracyCheck, MalformedCeilingRowsNameTheFileAndLine) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "penumbra-accuracy-malformed.csv";
  {
    std::ofstream out(file);
    out << "configuration,scene,technique,measured_rmse,ceiling_rmse\n"
           "default,bench,vsm,0.04,0.05\ndefault,bench,esm,0.1,lots\n";
  }
  try {
    compare::readAccuracyCeilings(file);
    FAIL() << "a malformed row must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("penumbra-accuracy-malformed.csv:3"), std::string::npos)
        << e.what();
  }
  for (const char* row : {"default,bench,esm,0.1x,0.2", "default,bench,esm,0.1,0.2,0.3",
                          "default,bench,vsm,0.04,0.06", "bench,vsm,0.04,0.06"}) {
    std::ofstream out(file);
    out << "configuration,scene,technique,measured_rmse,ceiling_rmse\n"
           "default,bench,vsm,0.04,0.05\n"
        << row << "\n";
    out.close();
    // junk, an extra column, a duplicate, a row of the old four-column table
    EXPECT_THROW(compare::readAccuracyCeilings(file), Error) << row;
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace penumbra
