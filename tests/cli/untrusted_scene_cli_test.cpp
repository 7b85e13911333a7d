// Hostile scene files through the commands that load them before any GL work (render, bench): a
// node chain deeper than the loader walks, JSON nested past the parser's safe depth, instances
// beyond --max-memory, OBJ side files that are devices or FIFOs. Each is one line naming the file
// and exit 1, and nothing is written. The files are generated in a scratch folder.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <functional>
#include <optional>

#include "../scene/scene_fixtures.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

const std::vector<glm::vec3> kQuad{
    {-0.5f, 0.0f, -0.5f}, {-0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, -0.5f}};
const std::vector<uint16_t> kQuadIndices{0, 1, 2, 0, 2, 3};

struct HostileFile {
  const char* name;
  // Writes the file into the folder and returns it.
  std::function<fs::path(const fs::path&)> write;
  std::vector<std::string> options;  // beyond --scene FILE
  // After "penumbra: error: FILE: "; %DIR% stands for the scratch folder, %ANY% for any text.
  const char* message;
};

// The issue's 400 KB file: 20,000 levels, which overflowed the stack of a recursive walk.
fs::path writeDeepChain(const fs::path& dir) {
  std::string nodes = "[";
  for (int i = 0; i + 1 < 20000; ++i) nodes += R"({"children":[)" + std::to_string(i + 1) + "]},";
  return penumbra::testing::writeFile(
      dir / "deep.gltf",
      penumbra::testing::gltfWithMesh(kQuad, kQuadIndices, nodes + R"({"mesh":0}])", "[0]"));
}

fs::path writeNestedExtras(const fs::path& dir) {
  return penumbra::testing::writeFile(
      dir / "nested.gltf",
      penumbra::testing::gltfWithMesh(
          kQuad, kQuadIndices, R"([{"mesh":0}])", "[0]", "",
          ",\"extras\":" + std::string(100000, '[') + std::string(100000, ']')));
}

// A 64 x 64 grid drawn by 100 nodes: 81.9 MiB once expanded.
fs::path writeInstances(const fs::path& dir) {
  const penumbra::testing::Grid g = penumbra::testing::grid(64);
  std::string nodes = "[", roots = "[";
  for (int i = 0; i < 100; ++i) {
    nodes += (i ? "," : "") + std::string(R"({"mesh":0})");
    roots += (i ? "," : "") + std::to_string(i);
  }
  return penumbra::testing::writeFile(
      dir / "instances.gltf",
      penumbra::testing::gltfWithMesh(g.positions, g.indices, nodes + "]", roots + "]"));
}

fs::path writeObjNaming(const fs::path& dir, const std::string& library, const std::string& mtl) {
  if (!mtl.empty()) penumbra::testing::writeFile(dir / "side.mtl", mtl);
  return penumbra::testing::writeFile(
      dir / "side.obj", "mtllib " + library + "\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n");
}

class HostileSceneFile : public ::testing::TestWithParam<HostileFile> {};

TEST_P(HostileSceneFile, IsRefusedByRenderAndBenchInOneLine) {
  ScratchFolder scratch;
  const fs::path file = GetParam().write(scratch.path());
  std::string expected = "penumbra: error: " + file.string() + ": " + GetParam().message + "\n";
  if (const size_t at = expected.find("%DIR%"); at != std::string::npos) {
    expected.replace(at, 5, scratch.path().string());
  }
  const size_t any = expected.find("%ANY%");
  const std::string head = expected.substr(0, any);
  const std::string tail = any == std::string::npos ? "" : expected.substr(any + 5);
  std::optional<penumbra::testing::FifoUnblocker> unblocker;
  if (fs::is_fifo(scratch.path() / "pipe.mtl")) unblocker.emplace(scratch.path() / "pipe.mtl");
  for (std::vector<std::string> command :
       {std::vector<std::string>{"render"},
        std::vector<std::string>{"bench", "--passes", "--technique", "vsm"}}) {
    command.insert(command.end(), {"--scene", file.string(), "--out", "out"});
    command.insert(command.end(), GetParam().options.begin(), GetParam().options.end());
    const RunResult run = runPenumbra(command, scratch.path());
    EXPECT_EQ(run.exitCode(), 1) << command[0] << ": " << run.output;
    if (any == std::string::npos) {
      EXPECT_EQ(run.output, expected) << command[0];
    } else {
      EXPECT_TRUE(run.output.starts_with(head) && run.output.ends_with(tail) &&
                  std::count(run.output.begin(), run.output.end(), '\n') == 1)
          << command[0] << ": " << run.output;
    }
    EXPECT_FALSE(fs::exists(scratch.path() / "out")) << command[0];
  }
}

INSTANTIATE_TEST_SUITE_P(
    UntrustedScene, HostileSceneFile,
    ::testing::Values(
        HostileFile{"deep_chain",
                    writeDeepChain,
                    {},
                    "the node hierarchy is deeper than 1024 levels (node 1024 is at level 1025 "
                    "below root 0); penumbra loads at most 1024 levels"},
        HostileFile{
            "nested_json",
            writeNestedExtras,
            {},
            "its JSON nests arrays and objects deeper than 128 levels (at byte %ANY% of the "
            "JSON); penumbra reads at most 128"},
        HostileFile{"instances_beyond_max_memory",
                    writeInstances,
                    {"--max-memory", "16"},
                    "needs 81.9 MiB of host memory for 793,800 triangles (81.8 MiB) and the %ANY% "
                    "of files read, above the 16.0 MiB limit (--max-memory)"},
        HostileFile{"obj_library_dev_zero",
                    [](const fs::path& dir) { return writeObjNaming(dir, "/dev/zero", ""); },
                    {},
                    "material library '/dev/zero' is not a regular file (/dev/zero is a "
                    "character device); a scene reads regular files only"},
        HostileFile{"obj_texture_dev_urandom",
                    [](const fs::path& dir) {
                      return writeObjNaming(dir, "side.mtl", "newmtl a\nmap_d /dev/urandom\n");
                    },
                    {},
                    "texture '/dev/urandom' is not a regular file (/dev/urandom is a character "
                    "device); a scene reads regular files only"},
        HostileFile{"obj_library_fifo",
                    [](const fs::path& dir) {
                      // Never written to: a loader that opens it blocking waits until the
                      // test's FifoUnblocker opens the other end.
                      mkfifo((dir / "pipe.mtl").c_str(), 0600);
                      return writeObjNaming(dir, "pipe.mtl", "");
                    },
                    {},
                    "material library 'pipe.mtl' is not a regular file (%DIR%/pipe.mtl is a "
                    "FIFO); a scene reads regular files only"}),
    [](const ::testing::TestParamInfo<HostileFile>& test) { return test.param.name; });

TEST(MaxMemory, IsASizeInMiBOrWithAUnitWithinItsRange) {
  ScratchFolder scratch;
  for (const auto& [value, message] : std::vector<std::pair<std::string, std::string>>{
           {"0", "--max-memory '0' is out of range [1.00 MiB, 1.00 PiB]"},
           {"2048T", "--max-memory '2048T' is out of range [1.00 MiB, 1.00 PiB]"},
           {"3Q",
            "--max-memory '3Q' has an unknown unit 'Q': use K, M, G or T (binary: K = "
            "1024 bytes), or none for MiB"},
           {"lots",
            "--max-memory 'lots' is not a memory size: give a number of MiB (512) or a "
            "number with a unit K, M, G or T (1.5G, 512MiB)"}}) {
    const RunResult run =
        runPenumbra({"render", "--max-memory", value, "--out", "out"}, scratch.path());
    EXPECT_EQ(run.exitCode(), 1) << run.output;
    EXPECT_EQ(run.output, "penumbra: error: " + message + "\n");
  }
}

}  // namespace
}  // namespace penumbra::test
