// Point lights end to end: `render --light point` and `compare` on the lantern scene give every
// technique a finite visibility in [0, 1], hard and soft (--light-size: a sphere light); matched
// PCF stays the filtered reference face by face; unknown light kinds are refused naming the valid
// choices.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "run_penumbra.h"

namespace penumbra::test {
namespace {

const char* const kTechniques[] = {"hard",  "pcf", "vsm", "lvsm",     "evsm2",
                                   "evsm4", "esm", "csm", "powercdf", "msm"};

// Every technique's render record in `folder`: a point light, visibility in [0,1], mostly lit
// (mean above 0.3) and shadowed somewhere (min below 0.5).
void expectPointLightVisibilityInUnitRange(const std::filesystem::path& folder,
                                           const std::string& scene) {
  for (const char* t : kTechniques) {
    const nlohmann::json record =
        nlohmann::json::parse(readFile(folder / (scene + "_" + t + ".json")));
    EXPECT_EQ(record["light_kind"], "point") << t;
    const nlohmann::json& v = record["visibility"];
    EXPECT_GE(v["min"].get<double>(), 0.0) << t;
    EXPECT_LE(v["max"].get<double>(), 1.0) << t;
    EXPECT_GT(v["mean"].get<double>(), 0.3) << t;
    EXPECT_LT(v["min"].get<double>(), 0.5) << t;
  }
}

TEST(PointLightCli, RenderGivesEveryTechniqueAVisibilityInUnitRange) {
  ScratchFolder scratch;
  const RunResult run = runPenumbra(
      {"render", "--scene", "backyard", "--light", "point", "--light-pos", "0,1.5,1", "--technique",
       "all", "--shadow-size", "128", "--width", "64", "--height", "36", "--out", "out"},
      scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  // Lit where nothing occludes (most of the ground), shadowed behind the fence and boxes.
  expectPointLightVisibilityInUnitRange(scratch.path() / "out", "backyard");
}

TEST(PointLightCli, CompareMeasuresEveryTechniqueAndMatchedPcfIsTheReference) {
  ScratchFolder scratch;
  const RunResult run = runPenumbra(
      {"compare", "--scene", "lantern", "--technique", "all", "--shadow-size", "128", "--width",
       "64", "--height", "64", "--frames", "2", "--supersample", "1", "--quiet", "--out", "report"},
      scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const nlohmann::json metrics =
      nlohmann::json::parse(readFile(scratch.path() / "report" / "metrics.json"));
  ASSERT_EQ(metrics["techniques"].size(), std::size(kTechniques));
  for (const nlohmann::json& t : metrics["techniques"]) {
    const double rmse = t["vs_filtered_reference"]["rmse"].get<double>();
    EXPECT_GE(rmse, 0.0) << t["technique"];
    EXPECT_LT(rmse, 0.5) << t["technique"];  // finite, and no technique is the inverse
    if (t["technique"] == "pcf") {
      // The same faces for PCF and the reference: matched PCF is the reference there (fp32).
      EXPECT_LT(t["vs_filtered_reference"]["max_absolute"].get<double>(), 1e-5);
    }
  }
}

TEST(PointLightCli, RenderWithALightSizeGivesEveryTechniqueASoftVisibilityInUnitRange) {
  ScratchFolder scratch;
  const RunResult run =
      runPenumbra({"render", "--scene", "lantern", "--light", "point", "--light-size", "0.3",
                   "--technique", "all", "--filter", "trilinear", "--shadow-size", "128", "--width",
                   "48", "--height", "48", "--out", "out"},
                  scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  // The room's walls are mostly lit, the cubes' own far sides and their shadows dark.
  expectPointLightVisibilityInUnitRange(scratch.path() / "out", "lantern");
}

TEST(PointLightCli, UnknownKindsAreRefusedNamingTheValidOnes) {
  ScratchFolder scratch;
  const RunResult unknown =
      runPenumbra({"render", "--light", "omni", "--out", "out"}, scratch.path());
  EXPECT_EQ(unknown.exitCode(), 1) << unknown.output;
  EXPECT_NE(unknown.output.find("valid kinds: directional, spot, point"), std::string::npos)
      << unknown.output;
  const RunResult tooBig = runPenumbra(
      {"render", "--scene", "lantern", "--light-size", "11", "--out", "out"}, scratch.path());
  EXPECT_EQ(tooBig.exitCode(), 1) << tooBig.output;
  EXPECT_NE(tooBig.output.find("for a point light (world units of sphere diameter)"),
            std::string::npos)
      << tooBig.output;
}

}  // namespace
}  // namespace penumbra::test
