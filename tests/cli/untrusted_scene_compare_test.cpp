// Hostile scene files through `penumbra compare`, which loads the scene once its GL context is
// up (gpu): a node chain deeper than the loader walks and instances beyond --max-memory are one
// line naming the file and exit 1, and no report is left behind. The files are generated in a
// scratch folder.
#include <gtest/gtest.h>

#include "../scene/scene_fixtures.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

const std::vector<glm::vec3> kQuad{
    {-0.5f, 0.0f, -0.5f}, {-0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, -0.5f}};
const std::vector<uint16_t> kQuadIndices{0, 1, 2, 0, 2, 3};

RunResult compare(const fs::path& scene, const std::vector<std::string>& options,
                  const fs::path& cwd) {
  std::vector<std::string> args{"compare",  "--scene", scene.string(),  "--technique", "vsm",
                                "--frames", "2",       "--supersample", "1",           "--quiet",
                                "--out",    "report"};
  args.insert(args.end(), options.begin(), options.end());
  return runPenumbra(args, cwd);
}

TEST(CompareUntrustedScene, RefusesTheTwentyThousandLevelChainInOneLine) {
  ScratchFolder scratch;
  std::string nodes = "[";
  for (int i = 0; i + 1 < 20000; ++i) nodes += R"({"children":[)" + std::to_string(i + 1) + "]},";
  const fs::path file = penumbra::testing::writeFile(
      scratch.path() / "deep.gltf",
      penumbra::testing::gltfWithMesh(kQuad, kQuadIndices, nodes + R"({"mesh":0}])", "[0]"));
  const RunResult run = compare(file, {}, scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_EQ(run.output, "penumbra: error: " + file.string() +
                            ": the node hierarchy is deeper than 1024 levels (node 1024 is at "
                            "level 1025 below root 0); penumbra loads at most 1024 levels\n");
  EXPECT_TRUE(entriesStartingWith(scratch.path(), "report").empty());
}

TEST(CompareUntrustedScene, RefusesInstancesBeyondMaxMemoryInOneLine) {
  ScratchFolder scratch;
  const penumbra::testing::Grid g = penumbra::testing::grid(64);
  std::string nodes = "[", roots = "[";
  for (int i = 0; i < 100; ++i) {
    nodes += (i ? "," : "") + std::string(R"({"mesh":0})");
    roots += (i ? "," : "") + std::to_string(i);
  }
  const fs::path file = penumbra::testing::writeFile(
      scratch.path() / "instances.gltf",
      penumbra::testing::gltfWithMesh(g.positions, g.indices, nodes + "]", roots + "]"));
  const RunResult run = compare(file, {"--max-memory", "16M"}, scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_TRUE(run.output.starts_with("penumbra: error: " + file.string() +
                                     ": needs 81.9 MiB of host memory for 793,800 triangles"))
      << run.output;
  EXPECT_TRUE(run.output.ends_with(", above the 16.0 MiB limit (--max-memory)\n")) << run.output;
  EXPECT_TRUE(entriesStartingWith(scratch.path(), "report").empty());
}

}  // namespace
}  // namespace penumbra::test
