// Scene files as untrusted input (docs/untrusted-input.md): hierarchies deeper than the loader
// walks, files that expand beyond the memory budget, unused and shared images, side files that
// are devices, FIFOs or too large, and failures the loaders did not foresee. Each ends in one
// line naming the file (or a correct scene), never a crash, a hang or unbounded memory. Every
// file is generated here, in the test's temporary folder.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>

#include "penumbra/error.h"
#include "penumbra/image.h"
#include "penumbra/image_io.h"
#include "penumbra/scene.h"
#include "scene_fixtures.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

const std::vector<glm::vec3> kQuad{
    {-0.5f, 0.0f, -0.5f}, {-0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, -0.5f}};
const std::vector<uint16_t> kQuadIndices{0, 1, 2, 0, 2, 3};
constexpr uint64_t kMiB = uint64_t(1) << 20;

// A fresh folder for one test.
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "penumbra_untrusted" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The message of the Error loadScene throws for `file`, or "loaded".
// Load options that bound the memory, for the file's geometry as written (no added ground).
SceneLoadOptions memoryLimit(uint64_t bytes) {
  SceneLoadOptions options;
  options.maxMemoryBytes = bytes;
  options.ground = GroundMode::Off;
  return options;
}

std::string refusal(const fs::path& file, const SceneLoadOptions& options = {}) {
  try {
    loadScene(file.string(), options);
    return "loaded";
  } catch (const Error& e) {
    return e.what();
  }
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Nodes 0 -> 1 -> ... -> depth - 1, each 1 mm above its parent, the quad at the last.
std::string nodeChain(int depth) {
  std::string nodes = "[";
  for (int i = 0; i + 1 < depth; ++i) {
    nodes += R"({"translation":[0,0.001,0],"children":[)" + std::to_string(i + 1) + "]},";
  }
  return nodes + R"({"translation":[0,0.001,0],"mesh":0}])";
}

fs::path writeChain(const fs::path& dir, int depth) {
  return testing::writeFile(dir / ("chain_" + std::to_string(depth) + ".gltf"),
                            testing::gltfWithMesh(kQuad, kQuadIndices, nodeChain(depth), "[0]"));
}

TEST(UntrustedGltf, WalksAHierarchyAtTheDepthLimit) {
  const Scene s = loadScene(writeChain(scratch("depth_limit"), kMaxGltfNodeDepth).string());
  EXPECT_EQ(s.triangleCount(), 2u);
  // 1024 levels of 1 mm: the quad at 1.024 m (a float sum of 1024 terms: within 1e-4).
  for (const Vertex& v : s.meshes[0].vertices) EXPECT_NEAR(v.position.y, 1.024f, 1e-4f);
}

TEST(UntrustedGltf, RefusesAHierarchyOneLevelDeeperThanTheLimitInOneLine) {
  const fs::path file = writeChain(scratch("depth_beyond"), kMaxGltfNodeDepth + 1);
  EXPECT_EQ(refusal(file), file.string() +
                               ": the node hierarchy is deeper than 1024 levels (node 1024 is at "
                               "level 1025 below root 0); penumbra loads at most 1024 levels");
}

// The issue's file: 400 KB, 20,000 levels. A recursive walk overflowed the thread's stack there
// (SIGSEGV in render, compare and the viewer).
TEST(UntrustedGltf, RefusesTheTwentyThousandLevelChainThatOverflowedTheStack) {
  const fs::path file = writeChain(scratch("depth_20000"), 20000);
  const std::string message = refusal(file);
  EXPECT_TRUE(contains(message, "the node hierarchy is deeper than 1024 levels")) << message;
  EXPECT_FALSE(contains(message, "\n"));
}

TEST(UntrustedGltf, StillRefusesACycleBelowADeepChain) {
  // 500 levels whose last node names node 250 as its child.
  std::string nodes = nodeChain(500);
  const std::string last = R"({"translation":[0,0.001,0],"mesh":0})";
  nodes.replace(nodes.rfind(last), last.size(),
                R"({"translation":[0,0.001,0],"mesh":0,"children":[250]})");
  const fs::path file =
      testing::writeFile(scratch("deep_cycle") / "cycle.gltf",
                         testing::gltfWithMesh(kQuad, kQuadIndices, nodes, "[0]"));
  const std::string message = refusal(file);
  EXPECT_TRUE(contains(message, "the node hierarchy is recursive: 0 -> 1 -> 2 -> ")) << message;
  EXPECT_TRUE(message.ends_with("498 -> 499 -> 250")) << message;
}

// tinygltf converts "extras" to its own values recursively: 100,000 nested arrays (200 KB)
// overflowed the stack as the deep node chain did.
TEST(UntrustedGltf, RefusesJsonNestedDeeperThanTheParserRecursesSafely) {
  const fs::path dir = scratch("json_nesting");
  const auto nested = [&](int depth) {
    return testing::writeFile(
        dir / ("extras_" + std::to_string(depth) + ".gltf"),
        testing::gltfWithMesh(
            kQuad, kQuadIndices, R"([{"mesh":0}])", "[0]", "",
            ",\"extras\":" + std::string(size_t(depth), '[') + std::string(size_t(depth), ']')));
  };
  const std::string message = refusal(nested(100000));
  EXPECT_TRUE(contains(message,
                       "extras_100000.gltf: its JSON nests arrays and objects deeper "
                       "than 128 levels"))
      << message;
  EXPECT_EQ(refusal(nested(100)), "loaded");
}

std::string littleEndianWord(uint32_t v) {
  return std::string{char(v & 0xff), char(v >> 8 & 0xff), char(v >> 16 & 0xff), char(v >> 24)};
}

void setWord(std::string& glb, size_t at, uint32_t v) {
  glb.replace(at, 4, littleEndianWord(v));
}

// A binary glTF (glTF 2.0 §4.4): the header, the JSON chunk padded with spaces, then `chunks`
// (each with its own header), the header's length counting them all.
std::string glb(std::string json, const std::string& chunks = "") {
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const uint32_t length = uint32_t(12 + 8 + json.size() + chunks.size());
  return "glTF" + littleEndianWord(2) + littleEndianWord(length) +
         littleEndianWord(uint32_t(json.size())) + "JSON" + json + chunks;
}

std::string chunk(const std::string& type, const std::string& data) {
  return littleEndianWord(uint32_t(data.size())) + type + data;
}

// The quad as a binary glTF, its positions and indices (60 bytes, little-endian on this host as
// on every host penumbra builds for) in the BIN chunk.
std::string quadGlb() {
  std::string bin(kQuad.size() * sizeof(glm::vec3) + kQuadIndices.size() * sizeof(uint16_t), '\0');
  std::memcpy(bin.data(), kQuad.data(), kQuad.size() * sizeof(glm::vec3));
  std::memcpy(bin.data() + kQuad.size() * sizeof(glm::vec3), kQuadIndices.data(),
              kQuadIndices.size() * sizeof(uint16_t));
  return glb(
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("buffers":[{"byteLength":60}],"bufferViews":[{"buffer":0,"byteLength":48},)"
      R"({"buffer":0,"byteOffset":48,"byteLength":12}],"accessors":[{"bufferView":0,)"
      R"("componentType":5126,"count":4,"type":"VEC3","min":[-0.5,0,-0.5],)"
      R"("max":[0.5,0,0.5]},{"bufferView":1,"componentType":5123,"count":6,)"
      R"("type":"SCALAR"}]})",
      chunk(std::string("BIN\0", 4), bin));
}

// The triangles of the scene in `file`, or the loader's message.
std::string loadedTriangles(const fs::path& file) {
  try {
    return std::to_string(loadScene(file.string(), memoryLimit(64 * kMiB)).triangleCount()) +
           " triangles";
  } catch (const Error& e) {
    return e.what();
  }
}

// A binary glTF's chunks must lie inside the length its header gives, and that inside the
// file. tinygltf checks the BIN chunk against that length without the chunk's own 8-byte
// header: with the length 8 short of the chunk's end and the file cut there, it read 8 bytes
// past the file (heap-buffer-overflow, found by scripts/fuzz-loaders; the quad's loader then
// read index 97 from beyond the file). Well-formed files load: with and without a BIN chunk,
// with a third chunk of a type nobody knows (the specification has readers skip it) and with
// bytes after the header's length.
TEST(UntrustedGltf, RefusesABinaryGltfWhoseChunksRunPastItsLength) {
  const fs::path dir = scratch("glb");
  const auto file = [&](const std::string& name, const std::string& bytes) {
    return testing::writeFile(dir / name, bytes);
  };
  const auto refused = [&](const std::string& name, const std::string& bytes) {
    return loadedTriangles(file(name, bytes)).substr((dir / name).string().size());
  };
  const std::string whole = quadGlb();
  EXPECT_EQ(loadedTriangles(file("quad.glb", whole)), "2 triangles");
  EXPECT_EQ(loadedTriangles(
                file("json_only.glb",
                     glb(testing::gltfWithMesh(kQuad, kQuadIndices, R"([{"mesh":0}])", "[0]")))),
            "2 triangles");
  std::string extra = whole + chunk("XTRA", "abcd");
  setWord(extra, 8, uint32_t(extra.size()));
  EXPECT_EQ(loadedTriangles(file("third_chunk.glb", extra)), "2 triangles");
  EXPECT_EQ(loadedTriangles(file("trailing.glb", whole + "tail")), "2 triangles");

  const size_t binHeader = whole.size() - 60 - 8;
  std::string past = whole.substr(0, whole.size() - 8);
  setWord(past, 8, uint32_t(past.size()));
  EXPECT_EQ(refused("past.glb", past),
            ": chunk 1 (at byte " + std::to_string(binHeader) +
                ") gives 60 bytes of data, but 52 are left of the length the binary glTF header "
                "gives");

  const std::string cut = whole.substr(0, whole.size() - 4);
  EXPECT_EQ(refused("cut.glb", cut),
            ": the binary glTF header gives a length of " + std::to_string(whole.size()) +
                " bytes (at byte 8), but the file holds " + std::to_string(cut.size()));

  std::string header = whole.substr(0, binHeader + 4);
  setWord(header, 8, uint32_t(header.size()));
  EXPECT_EQ(refused("chunk_header.glb", header),
            ": chunk 1's header (at byte " + std::to_string(binHeader) +
                ") needs 8 bytes, but 4 are left of the length the binary glTF header gives");

  std::string version1 = whole;
  setWord(version1, 4, 1);
  EXPECT_EQ(refused("v1.glb", version1),
            ": binary glTF version 1 (at byte 4); only version 2 is read");

  std::string binFirst = whole;
  setWord(binFirst, 16, 0x004E4942u);
  EXPECT_EQ(refused("bin_first.glb", binFirst),
            ": chunk 0 (at byte 12) is not JSON; a binary glTF starts with its JSON chunk");

  EXPECT_EQ(refused("empty_json.glb", glb("")), ": the JSON chunk (at byte 12) is empty");
  EXPECT_EQ(refused("short.glb", whole.substr(0, 16)),
            ": a binary glTF of 16 bytes is shorter than its 12-byte header and the JSON chunk's "
            "8-byte header");
}

// A 64 x 64 grid (7,938 triangles, no normals: three vertices each) drawn by 100 nodes.
fs::path writeInstances(const fs::path& dir, int side, int instances) {
  const testing::Grid g = testing::grid(side);
  std::string nodes = "[", roots = "[";
  for (int i = 0; i < instances; ++i) {
    nodes +=
        (i ? "," : "") + std::string(R"({"mesh":0,"translation":[0,)") + std::to_string(i) + ",0]}";
    roots += (i ? "," : "") + std::to_string(i);
  }
  return testing::writeFile(
      dir / "instances.gltf",
      testing::gltfWithMesh(g.positions, g.indices, nodes + "]", roots + "]"));
}

TEST(UntrustedGltf, BudgetsEveryInstanceOfAMeshBeforeExpandingIt) {
  const fs::path file = writeInstances(scratch("instances"), 64, 100);
  // 793,800 triangles, 2,381,400 vertices of 32 bytes and as many indices: 81.8 MiB.
  const std::string message = refusal(file, memoryLimit(16 * kMiB));
  EXPECT_TRUE(message.starts_with(file.string() +
                                  ": needs 81.9 MiB of host memory for 793,800 triangles (81.8 "
                                  "MiB) and the "))
      << message;
  EXPECT_TRUE(message.ends_with(" of files read, above the 16.0 MiB limit (--max-memory)"))
      << message;
  EXPECT_EQ(loadScene(file.string(), memoryLimit(256 * kMiB)).triangleCount(), 793800u);
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define PENUMBRA_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define PENUMBRA_SANITIZED 1
#endif
#endif

#ifndef PENUMBRA_SANITIZED
// The address space the process has mapped now, from /proc/self/status (VmSize, KiB).
uint64_t mappedBytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.starts_with("VmSize:")) return std::stoull(line.substr(7)) * 1024;
  }
  return 0;
}

// In a child process: loads `file` with 192 MiB of address space beyond what is mapped and
// the largest budget, prints the message and exits 1 when it is one line.
[[noreturn]] void loadWithLittleAddressSpace(const fs::path& file) {
  const uint64_t limit = mappedBytes() + 192 * kMiB;
  const rlimit addressSpace{limit, limit};
  setrlimit(RLIMIT_AS, &addressSpace);
  const std::string message = refusal(file, memoryLimit(kMaxSceneMemoryBytes));
  std::fprintf(stderr, "%s\n", message.c_str());
  std::exit(contains(message, "\n") ? 2 : 1);
}
#endif

// The budget is an estimate and the machine may hold less than it allows: a failed allocation
// still ends in one line naming the file. The file needs 850 MiB, the budget allows it, the
// child process can map 192 MiB more.
TEST(UntrustedGltf, TurnsAFailedAllocationIntoOneLineNamingTheFile) {
#ifdef PENUMBRA_SANITIZED
  GTEST_SKIP() << "the sanitizers reserve address space beyond any limit this test could set";
#else
  const fs::path file = writeInstances(scratch("out_of_memory"), 200, 100);
  EXPECT_EXIT(loadWithLittleAddressSpace(file), ::testing::ExitedWithCode(1),
              "instances.gltf: out of memory while loading the scene \\(within the 1.00 PiB "
              "limit");
#endif
}

// An image that says it is 8192 x 8192 and holds no pixels: its size reads from its header,
// decoding it fails with a warning.
fs::path writeHugeImage(const fs::path& dir) {
  return testing::writeFile(dir / "huge.png", testing::pngHeaderOnly(8192, 8192));
}

const std::string kTexturedMaterial =
    R"(,"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
    R"("textures":[{"source":0}])";

// The issue's file: 50 unreferenced entries of an 8192 x 8192 image decoded to 13.4 GB.
TEST(UntrustedGltf, DecodesOnlyTheImagesItsMaterialsUse) {
  const fs::path dir = scratch("unused_images");
  writeHugeImage(dir);
  std::string images = R"(,"images":[)";
  for (int i = 0; i < 50; ++i) images += std::string(i ? "," : "") + R"({"uri":"huge.png"})";
  const fs::path file = testing::writeFile(
      dir / "unused.gltf",
      testing::gltfWithMesh(kQuad, kQuadIndices, R"([{"mesh":0}])", "[0]", "", images + "]"));
  const Scene s = loadScene(file.string(), memoryLimit(16 * kMiB));
  EXPECT_TRUE(s.textures.empty());
  // Decoding any of them would have warned that it cannot be used.
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(UntrustedGltf, BudgetsTheImagesItsMaterialsUseFromTheirHeadersBeforeDecoding) {
  const fs::path dir = scratch("used_image");
  writeHugeImage(dir);
  const fs::path file = testing::writeFile(
      dir / "textured.gltf",
      testing::gltfWithMesh(kQuad, kQuadIndices, R"([{"mesh":0}])", "[0]", R"(,"material":0)",
                            kTexturedMaterial + R"(,"images":[{"uri":"huge.png"}])"));
  const std::string message = refusal(file, memoryLimit(64 * kMiB));
  EXPECT_TRUE(contains(message, "for 2 triangles (") && contains(message, "1 texture (256 MiB)") &&
              contains(message, "above the 64.0 MiB limit (--max-memory)"))
      << message;
  // Within the budget it is decoded, fails, and the material keeps its factor.
  const Scene s = loadScene(file.string(), memoryLimit(512 * kMiB));
  EXPECT_TRUE(s.textures.empty());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_TRUE(contains(s.warnings[0], "huge.png cannot be used: decoding failed")) << s.warnings[0];
}

struct SideFile {
  const char* name;     // the test's
  const char* obj;      // the OBJ's first line
  const char* mtl;      // side.mtl's texture line ("" for none)
  const char* message;  // after the file's name; %DIR% stands for the test's folder
};

class NonRegularObjSideFile : public ::testing::TestWithParam<SideFile> {};

TEST_P(NonRegularObjSideFile, IsRefusedInOneLine) {
  const fs::path dir = scratch(std::string("obj_") + GetParam().name);
  ASSERT_EQ(mkfifo((dir / "pipe").c_str(), 0600), 0);
  fs::create_directory(dir / "folder.png");
  fs::create_symlink("/dev/zero", dir / "zero.png");
  testing::writeFile(dir / "side.mtl", std::string("newmtl a\nKd 1 1 1\n") + GetParam().mtl + "\n");
  const fs::path file =
      testing::writeFile(dir / "side.obj", std::string(GetParam().obj) +
                                               "\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\n"
                                               "vt 1 1\nusemtl a\nf 1/1 2/2 3/3\n");
  const testing::FifoUnblocker unblocker(dir / "pipe");
  std::string expected = GetParam().message;
  if (const size_t at = expected.find("%DIR%"); at != std::string::npos) {
    expected.replace(at, 5, dir.string());
  }
  EXPECT_EQ(refusal(file), file.string() + ": " + expected);
}

INSTANTIATE_TEST_SUITE_P(
    UntrustedObj, NonRegularObjSideFile,
    ::testing::Values(
        SideFile{"library_dev_zero", "mtllib /dev/zero", "",
                 "material library '/dev/zero' is not a regular file (/dev/zero is a character "
                 "device); a scene reads regular files only"},
        SideFile{
            "library_fifo", "mtllib pipe", "",
            "material library 'pipe' is not a regular file (%DIR%/pipe is a FIFO); a scene reads "
            "regular files only"},
        SideFile{"map_kd_dev_zero", "mtllib side.mtl", "map_Kd /dev/zero",
                 "texture '/dev/zero' is not a regular file (/dev/zero is a character device); a "
                 "scene reads regular files only"},
        SideFile{"map_d_dev_urandom", "mtllib side.mtl", "map_d /dev/urandom",
                 "texture '/dev/urandom' is not a regular file (/dev/urandom is a character "
                 "device); a scene reads regular files only"},
        SideFile{
            "map_kd_fifo", "mtllib side.mtl", "map_Kd pipe",
            "texture 'pipe' is not a regular file (%DIR%/pipe is a FIFO); a scene reads regular "
            "files only"},
        SideFile{
            "map_kd_link_to_dev_zero", "mtllib side.mtl", "map_Kd zero.png",
            "texture 'zero.png' is not a regular file (%DIR%/zero.png is a character device); a "
            "scene reads regular files only"},
        SideFile{
            "map_kd_folder", "mtllib side.mtl", "map_Kd folder.png",
            "texture 'folder.png' is not a regular file (%DIR%/folder.png is a folder); a scene "
            "reads regular files only"}),
    [](const ::testing::TestParamInfo<SideFile>& test) { return test.param.name; });

TEST(UntrustedGltf, RefusesBuffersAndImagesThatAreNotRegularFiles) {
  const fs::path dir = scratch("gltf_side_files");
  ASSERT_EQ(mkfifo((dir / "pipe.png").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir / "zero.bin");
  fs::create_symlink("/dev/urandom", dir / "noise.png");
  const testing::FifoUnblocker unblocker(dir / "pipe.png");
  const auto withImage = [&](const std::string& uri) {
    return testing::writeFile(dir / (uri + ".gltf"),
                              testing::gltfWithMesh(kQuad, kQuadIndices, R"([{"mesh":0}])", "[0]",
                                                    "", R"(,"images":[{"uri":")" + uri + R"("}])"));
  };
  for (const char* uri : {"pipe.png", "noise.png"}) {
    const fs::path file = withImage(uri);
    const std::string message = refusal(file);
    EXPECT_TRUE(message.starts_with(file.string() + ": '" + (dir / uri).string() +
                                    "' is not a regular file"))
        << message;
  }
  const fs::path buffer = testing::writeFile(
      dir / "buffer.gltf",
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":16,"uri":"zero.bin"}]})");
  EXPECT_TRUE(contains(refusal(buffer), "zero.bin' is not a regular file")) << refusal(buffer);
}

// A sparse file: 2 GiB long, no disk used.
fs::path writeSparseFile(const fs::path& path) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  EXPECT_GE(fd, 0);
  EXPECT_EQ(ftruncate(fd, off_t(2048 * kMiB)), 0);
  close(fd);
  return path;
}

TEST(UntrustedSceneFiles, RefuseASideFileLargerThanTheBudgetBeforeReadingIt) {
  const fs::path dir = scratch("large_side_files");
  writeSparseFile(dir / "big.png");
  writeSparseFile(dir / "big.bin");
  testing::writeFile(dir / "big.mtl", "newmtl a\nmap_Kd big.png\n");
  const fs::path obj = testing::writeFile(
      dir / "big.obj", "mtllib big.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n");
  const std::string objMessage = refusal(obj, memoryLimit(64 * kMiB));
  EXPECT_TRUE(objMessage.starts_with(obj.string() + ": texture 'big.png' is 2.00 GiB, which takes "
                                                    "the files read to 2.00 GiB, above the 64.0 "
                                                    "MiB limit (--max-memory)"))
      << objMessage;
  const fs::path gltf = testing::writeFile(
      dir / "big.gltf",
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":16,"uri":"big.bin"}]})");
  const std::string gltfMessage = refusal(gltf, memoryLimit(64 * kMiB));
  EXPECT_TRUE(contains(gltfMessage, "big.bin' is 2.00 GiB, which takes the files read to"))
      << gltfMessage;
}

// 40 materials naming one colour texture, 20 more adding one mask to it: one image each read
// and decoded once, two scene textures (the colour alone, the colour with the mask's alpha).
TEST(UntrustedObj, DecodesATextureSharedByManyMaterialsOnce) {
  const fs::path dir = scratch("shared_texture");
  writeColorPng(Image(8, 8, 3, 0.5f), dir / "shared.png");
  writeColorPng(Image(4, 4, 3, 1.0f), dir / "mask.png");
  std::string mtl, faces;
  for (int i = 0; i < 60; ++i) {
    mtl += "newmtl m" + std::to_string(i) + "\nKd 1 1 1\nmap_Kd shared.png\n" +
           (i >= 40 ? "map_d mask.png\n" : "");
    faces += "usemtl m" + std::to_string(i) + "\nf 1/1 2/2 3/3\n";
  }
  testing::writeFile(dir / "shared.mtl", mtl);
  const fs::path file = testing::writeFile(
      dir / "shared.obj",
      "mtllib shared.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n" + faces);
  const Scene s = loadScene(file.string(), memoryLimit(4 * kMiB));
  ASSERT_EQ(s.meshes.size(), 60u);
  ASSERT_EQ(s.textures.size(), 2u);
  for (size_t m = 0; m < 60; ++m) EXPECT_EQ(s.meshes[m].baseColorTexture, m < 40 ? 0 : 1) << m;
  EXPECT_EQ(s.textures[0].width, 8);
  EXPECT_EQ(s.textures[1].width, 8);  // the colour's size, the mask's luminance as alpha
  EXPECT_EQ(s.textures[1].rgba[3], 255);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(UntrustedObj, WarnsOnceForATextureManyMaterialsNameThatCannotBeRead) {
  const fs::path dir = scratch("shared_missing_texture");
  std::string mtl, faces;
  for (int i = 0; i < 40; ++i) {
    mtl += "newmtl m" + std::to_string(i) + "\nmap_Kd missing.png\n";
    faces += "usemtl m" + std::to_string(i) + "\nf 1 2 3\n";
  }
  testing::writeFile(dir / "missing.mtl", mtl);
  const fs::path file = testing::writeFile(
      dir / "missing.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n" + faces);
  const Scene s = loadScene(file.string());
  EXPECT_TRUE(s.textures.empty());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0],
            file.string() + ": texture 'missing.png' cannot be used: it cannot be read");
}

TEST(UntrustedObj, BudgetsGeometryAndTexturesBeforeBuildingThem) {
  const fs::path dir = scratch("obj_budget");
  writeHugeImage(dir);
  testing::writeFile(dir / "huge.mtl", "newmtl a\nmap_Kd huge.png\n");
  const fs::path textured = testing::writeFile(
      dir / "textured.obj", "mtllib huge.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n");
  const std::string message = refusal(textured, memoryLimit(64 * kMiB));
  EXPECT_TRUE(contains(message, "for 1 triangle (") && contains(message, "1 texture (256 MiB)"))
      << message;
  // 20,000 faces: at most three vertices of 32 bytes and three indices each, 2.06 MiB.
  std::string faces = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";
  for (int i = 0; i < 20000; ++i) faces += "f 1 2 3\n";
  const fs::path many = testing::writeFile(dir / "many.obj", faces);
  const std::string manyMessage = refusal(many, memoryLimit(kMinSceneMemoryBytes));
  EXPECT_TRUE(contains(manyMessage, "for 20,000 triangles (2.06 MiB)")) << manyMessage;
  EXPECT_EQ(loadScene(many.string(), memoryLimit(16 * kMiB)).triangleCount(), 20000u);
}

TEST(SceneLoadOptions, ParsesMemorySizesInMiBOrWithABinaryUnit) {
  EXPECT_EQ(parseMemorySize("512", "--max-memory"), 512 * kMiB);
  EXPECT_EQ(parseMemorySize("1.5G", "--max-memory"), 1536 * kMiB);
  EXPECT_EQ(parseMemorySize("2GiB", "--max-memory"), 2048 * kMiB);
  EXPECT_EQ(parseMemorySize("64mb", "--max-memory"), 64 * kMiB);
  EXPECT_EQ(parseMemorySize("1024K", "--max-memory"), kMinSceneMemoryBytes);
  EXPECT_EQ(parseMemorySize("1024T", "--max-memory"), kMaxSceneMemoryBytes);
  const auto message = [](const char* text) {
    try {
      parseMemorySize(text, "--max-memory");
      return std::string("accepted");
    } catch (const Error& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(message("0"), "--max-memory '0' is out of range [1.00 MiB, 1.00 PiB]");
  EXPECT_EQ(message("1023K"), "--max-memory '1023K' is out of range [1.00 MiB, 1.00 PiB]");
  EXPECT_EQ(message("1025T"), "--max-memory '1025T' is out of range [1.00 MiB, 1.00 PiB]");
  EXPECT_TRUE(message("5X").starts_with("--max-memory '5X' has an unknown unit 'X'"));
  EXPECT_TRUE(message("2P").starts_with("--max-memory '2P' has an unknown unit 'P'"));
  for (const char* bad : {"", "-5", "big", " 5", "nan"}) {
    EXPECT_TRUE(contains(message(bad), "is not a memory size")) << bad;
  }
}

TEST(SceneLoadOptions, SaysSizesInThreeDigitsOfTheLargestBinaryUnit) {
  EXPECT_EQ(memorySizeText(0), "0 bytes");
  EXPECT_EQ(memorySizeText(1023), "1023 bytes");
  EXPECT_EQ(memorySizeText(1536), "1.50 KiB");
  EXPECT_EQ(memorySizeText(uint64_t(3.26 * double(1 << 30))), "3.26 GiB");
  EXPECT_EQ(memorySizeText(500 * kMiB), "500 MiB");
}

TEST(SceneLoadOptions, DefaultsToHalfThePhysicalMemoryAndRefusesLimitsOutOfRange) {
  const uint64_t physical = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  EXPECT_EQ(defaultSceneMemoryLimit(),
            std::clamp(physical / 2, kMinSceneMemoryBytes, kMaxSceneMemoryBytes));
  EXPECT_EQ(SceneLoadOptions{}.maxMemoryBytes, defaultSceneMemoryLimit());
  const fs::path file = writeChain(scratch("limit_range"), 1);
  EXPECT_EQ(refusal(file, memoryLimit(kMinSceneMemoryBytes - 1)),
            "the scene memory limit 1024 KiB is out of range [1.00 MiB, 1.00 PiB]");
}

}  // namespace
}  // namespace penumbra
