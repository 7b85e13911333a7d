// --camera list through every command that loads a scene file (render, compare, bench, tune):
// the file's perspective cameras numbered as --camera takes them, what the first
// kMaxFileCamerasJudged see and how many more were not judged, before any GL work; a camera the
// file has but --camera does not number is named by the file's own index.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../scene/scene_fixtures.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

// A unit quad at the origin, an orthographic camera (the file's camera 1, at node 1) and
// `count` perspective ones (the file's camera 0) named "view 0", "view 1", ... looking at the
// quad from 5, 6, ... units along +z.
fs::path writeCameras(const fs::path& dir, int count) {
  std::string nodes = R"([{"mesh":0},{"camera":1,"translation":[0,0,4]})";
  std::string roots = "[0,1";
  for (int i = 0; i < count; ++i) {
    nodes += R"(,{"name":"view )" + std::to_string(i) + R"(","camera":0,"translation":[0,0,)" +
             std::to_string(5 + i) + "]}";
    roots += "," + std::to_string(i + 2);
  }
  const std::vector<glm::vec3> quad{
      {-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}};
  return penumbra::testing::writeFile(
      dir / "cameras.gltf",
      penumbra::testing::gltfWithMesh(
          quad, {0, 1, 2, 0, 2, 3}, nodes + "]", roots + "]", "",
          R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.7,"znear":0.01}},)"
          R"({"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"zfar":10,"znear":0.01}}])"));
}

bool has(const std::string& output, const std::string& text) {
  return output.find(text) != std::string::npos;
}

TEST(CameraList, RenderNumbersTheCamerasAsCameraTakesThemAndJudgesTheFirstSixteen) {
  ScratchFolder scratch;
  writeCameras(scratch.path(), 20);
  const RunResult run =
      runPenumbra({"render", "--scene", "cameras.gltf", "--camera", "list"}, scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  EXPECT_TRUE(has(run.output, "cameras.gltf defines 20 cameras, numbered as --camera takes them"))
      << run.output;
  EXPECT_TRUE(has(run.output, "  0  view 0  at 0,0,5, fov ")) << run.output;
  EXPECT_TRUE(has(run.output, "  15  view 15  at 0,0,20, fov ")) << run.output;
  EXPECT_FALSE(has(run.output, "view 16")) << run.output;
  EXPECT_TRUE(has(run.output, "  4 more (16 to 19) not judged")) << run.output;
  EXPECT_TRUE(has(run.output, "100% of the model's surface")) << run.output;
  // The orthographic camera is the file's camera 1, not --camera 1 (view 1).
  EXPECT_TRUE(has(run.output, "the file's camera 1 (node 1) is orthographic")) << run.output;
  EXPECT_TRUE(entriesStartingWith(scratch.path(), "out").empty());  // nothing rendered
}

TEST(CameraList, RenderListsAFewCamerasWithoutSayingMore) {
  ScratchFolder scratch;
  writeCameras(scratch.path(), 2);
  const RunResult run =
      runPenumbra({"render", "--scene", "cameras.gltf", "--camera", "list"}, scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  EXPECT_TRUE(has(run.output, "defines 2 cameras")) << run.output;
  EXPECT_TRUE(has(run.output, "  1  view 1  at 0,0,6")) << run.output;
  EXPECT_FALSE(has(run.output, "not judged")) << run.output;
}

TEST(CameraList, BenchAndTuneListTooInsteadOfMeasuring) {
  ScratchFolder scratch;
  writeCameras(scratch.path(), 20);
  // Small enough that a command ignoring the list measures in seconds on llvmpipe.
  const std::vector<std::string> small{"--width", "32", "--height", "18", "--shadow-size", "64"};
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"bench", "--passes", "--technique", "vsm", "--repeat", "1"},
        std::vector<std::string>{"bench"},
        std::vector<std::string>{"tune", "--technique", "vsm", "--frames", "2", "--supersample",
                                 "1", "-q"}}) {
    std::vector<std::string> args = command;
    args.insert(args.end(), small.begin(), small.end());
    args.insert(args.end(), {"--scene", "cameras.gltf", "--camera", "list", "--out", "out"});
    const RunResult run = runPenumbra(args, scratch.path());
    EXPECT_EQ(run.exitCode(), 0) << command[0] << ": " << run.output;
    EXPECT_TRUE(has(run.output, "defines 20 cameras")) << command[0] << ": " << run.output;
    EXPECT_TRUE(has(run.output, "  4 more (16 to 19) not judged")) << run.output;
    EXPECT_FALSE(fs::exists(scratch.path() / "out")) << command[0];
    fs::remove_all(scratch.path() / "out");
  }
}

// The frame's sizes are checked before its aspect shapes the scene or judges its cameras.
TEST(CameraList, BenchRefusesAFrameWithoutHeightFirst) {
  ScratchFolder scratch;
  writeCameras(scratch.path(), 1);
  const RunResult run = runPenumbra(
      {"bench", "--scene", "cameras.gltf", "--camera", "list", "--height", "0"}, scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_TRUE(has(run.output, "frame height 0 is out of range")) << run.output;
  EXPECT_FALSE(has(run.output, "defines")) << run.output;
}

}  // namespace
}  // namespace penumbra::test
