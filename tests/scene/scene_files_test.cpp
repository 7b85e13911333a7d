// The glTF 2.0 and OBJ loaders on Debian's assimp-testmodels (valid and deliberately broken
// files) and on generated fixtures; view overrides.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "load_as_written.h"
#include "penumbra/error.h"
#include "penumbra/image.h"
#include "penumbra/image_io.h"
#include "penumbra/scene.h"
#include "scene_fixtures.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
const fs::path kModels = "/usr/share/assimp/models";

bool allFinite(const Scene& scene) {
  for (const Mesh& m : scene.meshes) {
    for (const Vertex& v : m.vertices) {
      const float sum = v.position.x + v.position.y + v.position.z + v.normal.x + v.normal.y +
                        v.normal.z + v.texcoord.x + v.texcoord.y;
      if (!std::isfinite(sum) || std::abs(glm::length(v.normal) - 1.0f) > 1e-4f) return false;
    }
  }
  return true;
}

TEST(GltfLoader, LoadsTheTwoCylinderEngineWithItsCameraAndEveryTriangle) {
  const Scene s = testing::loadAsWritten(
      (kModels / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string());
  EXPECT_EQ(s.name, "2CylinderEngine");
  EXPECT_EQ(s.triangleCount(), 121496u);  // the sum of its primitives' index counts / 3
  EXPECT_TRUE(allFinite(s));
  ASSERT_EQ(s.fileCameras.size(), 1u);
  EXPECT_NEAR(s.fileCameras[0].camera.verticalFovDegrees, 18.0107f, 1e-3f);  // its yfov
  // Its camera crops the engine at 16:9 (99.2% of the surface in view): the framing camera.
  EXPECT_EQ(s.camera.verticalFovDegrees, 45.0f);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("its camera does not see the whole model"), std::string::npos)
      << s.warnings[0];
  EXPECT_TRUE(s.troubleSpots.empty());
}

TEST(GltfLoader, ReadsTheBaseColourTextureAsRgba8) {
  for (const char* file :
       {"glTF2/BoxTextured-glTF/BoxTextured.gltf", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
        "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    const Scene s = testing::loadAsWritten((kModels / file).string());
    ASSERT_EQ(s.textures.size(), 1u) << file;
    EXPECT_EQ(s.textures[0].width, 211) << file;  // CesiumLogoFlat.png
    EXPECT_EQ(s.textures[0].rgba.size(), size_t(211 * 211 * 4)) << file;
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].baseColorTexture, 0) << file;
    EXPECT_TRUE(allFinite(s)) << file;
  }
}

TEST(GltfLoader, ReplacesZeroNormalsWithTriangleNormalsAndWarns) {
  const Scene s = testing::loadAsWritten(
      (kModels / "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb").string());
  EXPECT_TRUE(allFinite(s));
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("normals were not finite or had zero length"), std::string::npos);
}

TEST(GltfLoader, ConvertsStripsAndFansToTriangles) {
  // Mesh_PrimitiveMode_04..06: a square as triangles, a strip and a fan: two triangles each.
  for (int mode : {4, 5, 6}) {
    const fs::path f =
        kModels / ("glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_0" +
                   std::to_string(mode) + ".gltf");
    const Scene s = testing::loadAsWritten(f.string());
    EXPECT_EQ(s.triangleCount(), 2u) << f;
    // Counter-clockwise seen from +z (the file's front): every normal points at +z.
    for (const Vertex& v : s.meshes[0].vertices) EXPECT_GT(v.normal.z, 0.99f) << f;
  }
}

struct BrokenFile {
  const char* path;
  const char* message;  // what the error must say after the file's name
};

class BrokenGltf : public ::testing::TestWithParam<BrokenFile> {};

TEST_P(BrokenGltf, IsRefusedWithAnErrorNamingTheFileAndTheFault) {
  const fs::path path = kModels / "glTF2" / GetParam().path;
  try {
    testing::loadAsWritten(path.string());
    FAIL() << path << " loaded";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(GetParam().message), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    AssimpTestModels, BrokenGltf,
    ::testing::Values(
        BrokenFile{"IndexOutOfRange/IndexOutOfRange.gltf",
                   "index 255 at position 0 is out of range (the primitive has 24 vertices)"},
        BrokenFile{"IndexOutOfRange/AllIndicesOutOfRange.gltf", "index 65535 at position 0"},
        BrokenFile{"MissingBin/BoxTextured.gltf", "File not found : BoxTextured0.bin"},
        BrokenFile{"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
                   "POSITION (accessor 2) element 0 is not finite"},
        BrokenFile{"RecursiveNodes/RecursiveNodes.gltf",
                   "the node hierarchy is recursive: 0 -> 1 -> 0"},
        BrokenFile{"TestNoRootNode/NoScene.gltf", "the file has no scene"},
        BrokenFile{"TestNoRootNode/SceneWithoutNodes.gltf", "the scene has no nodes"},
        BrokenFile{"SchemaFailures/sceneWrongType.gltf",
                   "scene must be a non-negative integer (it is a string)"},
        BrokenFile{"wrongTypes/badArray.gltf",
                   "meshes[0].primitives must be an array of objects (it is an object)"},
        BrokenFile{"wrongTypes/badExtension.gltf",
                   "baseColorTexture.extensions.KHR_texture_transform must be an object"},
        BrokenFile{"wrongTypes/badNumber.gltf",
                   "materials[0].normalTexture.scale must be a number (it is a string)"},
        BrokenFile{"wrongTypes/badObject.gltf",
                   "materials[0].pbrMetallicRoughness must be an object (it is an array)"},
        BrokenFile{"wrongTypes/badString.gltf", "scenes[0].name must be a string"},
        BrokenFile{"wrongTypes/badUint.gltf",
                   "baseColorTexture.index must be a non-negative integer (it is negative)"},
        BrokenFile{"IncorrectVertexArrays/Cube.gltf", "draws lines (mode 1)"},
        BrokenFile{"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf",
                   "draws points (mode 0)"},
        BrokenFile{"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf",
                   "requires extension KHR_technique_webgl"}));

// A quad of side 1 in the xz plane around the origin, facing +y.
const std::vector<glm::vec3> kQuad{
    {-0.5f, 0.0f, -0.5f}, {-0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, -0.5f}};
const std::vector<uint16_t> kQuadIndices{0, 1, 2, 0, 2, 3};

// Found by the fuzzer: tinygltf 2.7 passed an image's buffer view to the decoder unchecked.
TEST(GltfLoader, RefusesAnImageWhoseBufferViewRunsPastItsBuffer) {
  const fs::path file = fs::path(PENUMBRA_TEST_DATA_DIR) / "fuzz_image_view_past_buffer.glb";
  try {
    testing::loadAsWritten(file.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("runs past the end of its buffer"), std::string::npos)
        << e.what();
  }
}

// Found by the fuzzer (2026-12-07): tinygltf bounds a GLB's BIN chunk by the header's length
// without the chunk's 8-byte header, and this file's BIN chunk ends 8 bytes past that length and
// 3 past the file: tinygltf read past the heap buffer. The fuzzer also changed the version to
// 770, which is refused first; with the version mended in place, the chunk's bounds are.
TEST(GltfLoader, RefusesTheFuzzersGlbWhoseBinChunkRunsPastTheFile) {
  const fs::path kept = fs::path(PENUMBRA_TEST_DATA_DIR) / "fuzz_glb_bin_chunk_past_file.glb";
  const auto message = [](const fs::path& file) {
    try {
      testing::loadAsWritten(file.string());
      return std::string("loaded");
    } catch (const Error& e) {
      return std::string(e.what()).substr(file.string().size());
    }
  };
  EXPECT_EQ(message(kept), ": binary glTF version 770 (at byte 4); only version 2 is read");
  std::ifstream in(kept, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_EQ(bytes.size(), 1921u);
  bytes[4] = 2;
  bytes[5] = 0;
  const fs::path mended =
      testing::writeFile(fs::path(::testing::TempDir()) / "glb_bin_chunk_past_file.glb", bytes);
  EXPECT_EQ(message(mended),
            ": chunk 1 (at byte 1196) gives 720 bytes of data, but 712 are left of the length "
            "the binary glTF header gives");
}

// Found by the fuzzer: a PNG whose first IDAT chunk is empty made stb_image copy zero bytes to a
// null pointer (undefined behaviour: the sanitizer build aborts on it). Empty data chunks are
// dropped before decoding. Images are decoded when a material uses them: the fuzzer's file
// misspells its material's "pbrMetallicRoughness" and names texture 1 of 1, mended here in
// place (the GLB's chunk sizes hold). The file then fails on a mesh index out of range, a clear
// error, which the loader must reach.
TEST(GltfLoader, APngWithAnEmptyFirstDataChunkIsDecodedWithoutUndefinedBehaviour) {
  std::ifstream in(fs::path(PENUMBRA_TEST_DATA_DIR) / "fuzz_png_empty_first_idat.glb",
                   std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const size_t misspelt = bytes.find("pbrMe|allicRoughness");
  ASSERT_NE(misspelt, std::string::npos);
  bytes.replace(misspelt, 20, "pbrMetallicRoughness");
  const size_t texture = bytes.find(R"("baseColorTexture":{"index":1})");
  ASSERT_NE(texture, std::string::npos);
  bytes[texture + 28] = '0';
  const fs::path file =
      testing::writeFile(fs::path(::testing::TempDir()) / "png_empty_first_idat.glb", bytes);
  try {
    testing::loadAsWritten(file.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is out of range"), std::string::npos) << e.what();
  }
}

TEST(GltfLoader, ComposesNodeTransformsParentFirst) {
  // Root: T(0,1,0) R(y, 30 degrees) S(1.5); child: T(0.5,0,0) with the quad.
  const std::string nodes =
      R"([{"translation":[0,1,0],"rotation":[0,0.258819045,0,0.965925826],"scale":[1.5,1.5,1.5],)"
      R"("children":[1]},{"translation":[0.5,0,0],"mesh":0}])";
  const fs::path file =
      testing::writeFile(fs::path(::testing::TempDir()) / "hierarchy.gltf",
                         testing::gltfWithMesh(kQuad, kQuadIndices, nodes, "[0]"));
  const Scene s = testing::loadAsWritten(file.string());
  ASSERT_EQ(s.meshes.size(), 1u);
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)) *
                          glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0)) *
                          glm::scale(glm::mat4(1.0f), glm::vec3(1.5f)) *
                          glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0, 0));
  // Without normals in the file every triangle corner is a vertex of its own (flat normals).
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.indices.size(), kQuadIndices.size());
  for (size_t k = 0; k < m.indices.size(); ++k) {
    const glm::vec3 expected(world * glm::vec4(kQuad[kQuadIndices[k]], 1.0f));
    // The file's quaternion has 9 digits: 1e-5 m.
    EXPECT_LT(glm::length(m.vertices[m.indices[k]].position - expected), 1e-5f) << k;
  }
}

TEST(GltfLoader, RefusesANodeWithTwoParents) {
  const std::string nodes = R"([{"children":[2]},{"children":[2]},{"mesh":0}])";
  const fs::path file =
      testing::writeFile(fs::path(::testing::TempDir()) / "two_parents.gltf",
                         testing::gltfWithMesh(kQuad, kQuadIndices, nodes, "[0,1]"));
  EXPECT_THROW(
      {
        try {
          testing::loadAsWritten(file.string());
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("node 2 is reached twice"), std::string::npos)
              << e.what();
          throw;
        }
      },
      Error);
}

TEST(GltfLoader, ComputesFlatNormalsWhereTheFileHasNone) {
  const fs::path file =
      testing::writeFile(fs::path(::testing::TempDir()) / "flat.gltf",
                         testing::gltfWithMesh(kQuad, kQuadIndices, R"([{"mesh":0}])", "[0]"));
  const Scene s = testing::loadAsWritten(file.string());
  ASSERT_EQ(s.meshes[0].vertices.size(), 6u);  // one vertex per triangle corner
  for (const Vertex& v : s.meshes[0].vertices) EXPECT_EQ(v.normal, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(ObjLoader, ReadsMapDAsTheAlphaMaskOfMapKd) {
  const fs::path dir = fs::path(::testing::TempDir()) / "obj_map_d";
  // The mask: white left half, black right half (4 x 2 texels); the colour: all red.
  Image mask(4, 2, 3, 0.0f), colour(4, 2, 3, 0.0f);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) {
      for (int c = 0; c < 3; ++c) mask.at(x, y, c) = x < 2 ? 1.0f : 0.0f;
      colour.at(x, y, 0) = 1.0f;
    }
  }
  fs::create_directories(dir);
  writeColorPng(mask, dir / "leaf_mask.png");
  writeColorPng(colour, dir / "leaf.png");
  testing::writeFile(dir / "leaf.mtl",
                     "newmtl leaf\nKd 1 1 1\nmap_Kd leaf.png\nmap_d leaf_mask.png\n");
  testing::writeFile(dir / "leaf.obj",
                     "mtllib leaf.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl leaf\nf 1/1 2/2 3/3 4/4\n");
  const Scene s = testing::loadAsWritten((dir / "leaf.obj").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
  EXPECT_EQ(s.triangleCount(), 2u);  // the quad as a fan
  ASSERT_EQ(m.baseColorTexture, 0);
  const TextureImage& t = s.textures[0];
  ASSERT_EQ(t.width, 4);
  for (int x = 0; x < 4; ++x) {
    EXPECT_EQ(t.rgba[size_t(x) * 4 + 0], 255);                   // red from map_Kd
    EXPECT_EQ(t.rgba[size_t(x) * 4 + 3], x < 2 ? 255 : 0) << x;  // alpha from map_d
  }
  // OBJ's v = 0 is the image's bottom row; penumbra's texcoord y = 0 its top row.
  EXPECT_EQ(m.vertices[0].texcoord, glm::vec2(0.0f, 1.0f));
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(ObjLoader, RefusesAFaceNamingAVertexTheFileDoesNotHave) {
  const fs::path file = testing::writeFile(fs::path(::testing::TempDir()) / "bad_index.obj",
                                           "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n");
  try {
    testing::loadAsWritten(file.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("names vertex 7, but the file has 3"), std::string::npos)
        << e.what();
  }
}

TEST(ObjLoader, RefusesASkinWeightJointBeyondInt) {
  // The fuzzer's find: tinyobjloader would convert the joint to int, undefined behaviour.
  const fs::path file = fs::path(PENUMBRA_TEST_DATA_DIR) / "fuzz_vw_joint_beyond_int.obj";
  try {
    testing::loadAsWritten(file.string());
    FAIL();
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("fuzz_vw_joint_beyond_int.obj: line 1: skin weight (vw) joint "
                           "'6000000000' is outside int's range"),
              std::string::npos)
        << message;
  }
  // In range, with CRLF line ends and tabs: loads (tinyobjloader keeps the weights, penumbra
  // ignores them).
  const fs::path valid = testing::writeFile(
      fs::path(::testing::TempDir()) / "skin_weights.obj",
      "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nvw 1\t0 0.5 2147483647 0.5\r\nf 1 2 3\r\n");
  EXPECT_EQ(testing::loadAsWritten(valid.string()).triangleCount(), 1u);
  const fs::path negative =
      testing::writeFile(fs::path(::testing::TempDir()) / "negative.obj", "v 0 0 0\nvw 0 -3e9 1\n");
  EXPECT_THROW(testing::loadAsWritten(negative.string()), Error)
      << "below int's range is undefined too";
  const fs::path later = testing::writeFile(fs::path(::testing::TempDir()) / "late_joint.obj",
                                            "v 0 0 0\rv 1 0 0\nvw 1 0 0.5 1e10 0.5\n");
  EXPECT_THROW(
      {
        try {
          testing::loadAsWritten(later.string());
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("line 3: skin weight (vw) joint '1e10'"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      Error);
}

TEST(ObjLoader, RefusesNonFinitePositions) {
  const fs::path file = testing::writeFile(fs::path(::testing::TempDir()) / "nan.obj",
                                           "v 0 0 0\nv 1 0 0\nv 1e400 1 0\nf 1 2 3\n");
  EXPECT_THROW(testing::loadAsWritten(file.string()), Error);
}

TEST(ObjLoader, LoadsTheAssimpTestModels) {
  for (const char* file : {"OBJ/spider.obj", "OBJ/WusonOBJ.obj", "OBJ/box.obj"}) {
    const Scene s = testing::loadAsWritten((kModels / file).string());
    EXPECT_GT(s.triangleCount(), 0u) << file;
    EXPECT_TRUE(allFinite(s)) << file;
  }
  // spider.mtl names its textures with Windows separators (".\\SpiderTex.jpg"); its faces use
  // four of its five materials.
  EXPECT_EQ(testing::loadAsWritten((kModels / "OBJ/spider.obj").string()).textures.size(), 4u);
}

TEST(SceneSource, NamesTheValidScenesAndExtensionsForAnythingElse) {
  try {
    testing::loadAsWritten("garden");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("foliage, penumbrae, lantern, or a .gltf, .glb or .obj file"),
        std::string::npos);
  }
  EXPECT_THROW(testing::loadAsWritten("/nonexistent/model.glb"), Error);
}

TEST(SceneOverrides, SetTheLightAndCameraAndRefuseNonsense) {
  Scene s = makeBuiltinScene("planar");
  SceneOverrides o;
  o.lightPosition = glm::vec3(0.0f, 5.0f, 0.0f);
  o.cameraPosition = glm::vec3(1.0f, 2.0f, 3.0f);
  applyOverrides(s, o);
  EXPECT_EQ(s.light.kind, LightKind::Spot);
  EXPECT_EQ(s.light.target, s.modelBounds().centre());
  EXPECT_EQ(s.camera.position, glm::vec3(1.0f, 2.0f, 3.0f));
  SceneOverrides zero;
  zero.lightDirection = glm::vec3(0.0f);
  EXPECT_THROW(applyOverrides(s, zero), Error);
  SceneOverrides both;
  both.lightDirection = glm::vec3(0.0f, -1.0f, 0.0f);
  both.lightPosition = glm::vec3(0.0f, 1.0f, 0.0f);
  EXPECT_THROW(applyOverrides(s, both), Error);
  SceneOverrides infinite;
  infinite.cameraTarget = glm::vec3(INFINITY, 0.0f, 0.0f);
  EXPECT_THROW(applyOverrides(s, infinite), Error);
}

TEST(FoliageScene, HasAlphaMaskedLeafCardsWithHoles) {
  const Scene s = makeBuiltinScene("foliage");
  ASSERT_EQ(s.textures.size(), 1u);
  size_t covered = 0;
  const std::vector<uint8_t>& rgba = s.textures[0].rgba;
  for (size_t i = 3; i < rgba.size(); i += 4) covered += rgba[i] == 255;
  const double coverage = double(covered) / double(rgba.size() / 4);
  // Seven ellipses of 0.2 x 0.075 (pi ab = 0.047 each, a little overlap): about a third.
  EXPECT_GT(coverage, 0.25);
  EXPECT_LT(coverage, 0.35);
  size_t masked = 0;
  for (const Mesh& m : s.meshes)
    masked += m.alphaMode == AlphaMode::Mask && m.baseColorTexture == 0;
  EXPECT_EQ(masked, 2u);  // the crown and the hedge
}

}  // namespace
}  // namespace penumbra
