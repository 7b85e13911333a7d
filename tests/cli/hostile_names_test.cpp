// Issue 23's repros through a whole comparison: a scene file and a report folder whose names hold
// backquotes and $( ) ran commands through gnuplot; now both are only names. The report is
// written under the literal folder name, its plots exist, and no command ran.
#include <gtest/gtest.h>

#include "run_penumbra.h"

namespace penumbra::test {
namespace {

TEST(HostileNames, SceneFileAndReportFolderNamesRunNothing) {
  ScratchFolder scratch;
  const fs::path model = "/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
  ASSERT_TRUE(fs::exists(model)) << "Debian's assimp-testmodels (scripts/install-deps)";
  const std::string scene = "truck`touch PWNED`$(touch PWNED1)'.glb";
  const std::string out = "o`touch PWNED2`$(touch PWNED3)";
  fs::copy_file(model, scratch.path() / scene);
  const RunResult run = runPenumbra(
      {"compare", "--scene", scene, "--technique", "hard,pcf", "--shadow-size", "128", "--width",
       "64", "--height", "36", "--frames", "2", "--supersample", "1", "--quiet", "--out", out},
      scratch.path(), {{"TMPDIR", (scratch.path() / "t;touch PWNED4;").string()}});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  EXPECT_TRUE(fs::exists(scratch.path() / out / "index.html"));
  EXPECT_TRUE(fs::exists(scratch.path() / out / "grid.png"));
  // Nothing but the model and the report: no PWNED*, no gnuplot scratch folder or log.
  std::vector<std::string> top;
  for (const auto& entry : fs::directory_iterator(scratch.path())) {
    top.push_back(entry.path().filename().string());
  }
  std::sort(top.begin(), top.end());
  EXPECT_EQ(top, (std::vector<std::string>{out, scene}));
  for (const auto& entry : fs::recursive_directory_iterator(scratch.path() / out)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find("PWNED"), std::string::npos) << entry.path();
    EXPECT_EQ(name.find(".gnuplot-"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace penumbra::test
