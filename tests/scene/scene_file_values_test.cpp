// Values in scene files (docs/untrusted-input.md, "Values"): every non-finite number an OBJ, its
// material library or a glTF's used accessors and material factors hold is refused in one line
// naming the file, the place and the value, never read as 0 or as a vanished mesh; glTF BLEND is
// drawn as a mask with a warning. Every file is generated here, in the test's temporary folder.
#include <gtest/gtest.h>

#include <cmath>

#include <cstring>
#include <limits>

#include "load_as_written.h"
#include "penumbra/error.h"
#include "penumbra/image_io.h"
#include "penumbra/scene.h"
#include "scene_fixtures.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "penumbra_values" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The message of the Error loadScene throws for `file`, or "loaded".
std::string refusal(const fs::path& file) {
  try {
    testing::loadAsWritten(file.string());
    return "loaded";
  } catch (const Error& e) {
    return e.what();
  }
}

struct ObjValue {
  const char* name;     // the test's
  const char* obj;      // the OBJ
  const char* mtl;      // lib.mtl, beside it
  const char* message;  // after "<dir>/values.obj: "
};

class NonFiniteObjValue : public ::testing::TestWithParam<ObjValue> {};

TEST_P(NonFiniteObjValue, IsRefusedWithItsLineAndValue) {
  const fs::path dir = scratch(GetParam().name);
  testing::writeFile(dir / "lib.mtl", GetParam().mtl);
  const fs::path file = testing::writeFile(dir / "values.obj", GetParam().obj);
  EXPECT_EQ(refusal(file), file.string() + ": " + GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(
    UntrustedObj, NonFiniteObjValue,
    ::testing::Values(
        // tinyobjloader read "nan" and "inf" as 0: the vertex moved to the origin, rc 0.
        ObjValue{"v_nan", "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "",
                 "line 4: v value 'nan' is not a finite number"},
        ObjValue{"v_inf", "v 0 0 0\nv 1 0 0\nv 1 -inf 0\nf 1 2 3\n", "",
                 "line 3: v value '-inf' is not a finite number"},
        ObjValue{"v_infinity_tab", "v 0 0 0\r\nv 1 0 0\r\nv\t1\tInfinity\t0\r\nf 1 2 3\r\n", "",
                 "line 3: v value 'Infinity' is not a finite number"},
        // Refused before too, as an infinite position of "mesh 0, vertex 2": now by its line.
        ObjValue{"v_1e39", "v 0 0 0\nv 1 0 0\nv 1e39 1 0\nf 1 2 3\n", "",
                 "line 3: v value '1e39' is beyond single precision (at most 3.4e38 in "
                 "magnitude)"},
        ObjValue{"v_colour", "v 0 0 0\nv 1 0 0\nv 1 1 0 1 nan 1\nf 1 2 3\n", "",
                 "line 3: v value 'nan' is not a finite number"},
        ObjValue{"vt_nan", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt nan 0\nvt 1 1\nf 1/1 2/2 3/3\n",
                 "", "line 5: vt value 'nan' is not a finite number"},
        ObjValue{"vn_inf", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 inf 1\nf 1//1 2//1 3//1\n", "",
                 "line 4: vn value 'inf' is not a finite number"},
        // strtod reads 0e500 as 0; tinyobjloader as 0 x 5^500 = 0 x infinity, NaN.
        ObjValue{"v_tinyobjloader_nan", "v 0 0 0\nv 1 0 0\nv 0e500 1 0\nf 1 2 3\n", "",
                 "line 3: v value 1 is not finite as tinyobjloader reads it (nan)"},
        // A bare "v" is no statement to tinyobjloader, "v " (a trailing space) one at 0: the
        // line is still the right one.
        ObjValue{"v_tinyobjloader_nan_after_bare_v", "v\nv \nv 1 0 0\nv 0e500 1 0\nf 1 2 3\n", "",
                 "line 4: v value 1 is not finite as tinyobjloader reads it (nan)"},
        // `d nan` was 0: the material's geometry vanished, rc 0.
        ObjValue{"d_nan", "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n",
                 "newmtl a\nKd 1 1 1\nd nan\n",
                 "material library 'lib.mtl': line 3: d value 'nan' is not a finite number"},
        ObjValue{"tr_inf", "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n",
                 "newmtl a\nTr inf\n",
                 "material library 'lib.mtl': line 2: Tr value 'inf' is not a finite number"},
        // Kd 1e39 was clamped to 1; Kd nan read as 0.
        ObjValue{"kd_1e39", "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n",
                 "newmtl a\nKd 1e39 0 0\n",
                 "material library 'lib.mtl': line 2: Kd value '1e39' is beyond single "
                 "precision (at most 3.4e38 in magnitude)"},
        ObjValue{"kd_nan", "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n",
                 "# a comment\nnewmtl a\n  Kd 1 NaN 1\n",
                 "material library 'lib.mtl': line 3: Kd value 'NaN' is not a finite number"},
        ObjValue{"d_tinyobjloader_nan",
                 "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n",
                 "newmtl a\nd 0e500\n",
                 "material library 'lib.mtl': material 'a': d (or Tr) is not finite as "
                 "tinyobjloader reads it (nan)"}),
    [](const ::testing::TestParamInfo<ObjValue>& param) { return std::string(param.param.name); });

TEST(UntrustedObj, ReadsFiniteNumbersAndCommentsAsBefore) {
  const fs::path dir = scratch("finite");
  // 3.4028235e38 is above the largest float (3.40282347e38) but rounds to it: finite. "nan"
  // after "#" is a comment.
  testing::writeFile(dir / "lib.mtl", "newmtl a\nKd 0.5 0.25 1 # nan\nd 1\nNs 3.4028235e38\n");
  const fs::path file = testing::writeFile(
      dir / "finite.obj",
      "mtllib lib.mtl\nv 0 0 0 # nan\nv 1 0 0\nv 1 1 -1e-30\nusemtl a\nf 1 2 3\n");
  const Scene s = testing::loadAsWritten(file.string());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].albedo, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(s.meshes[0].alphaMode, AlphaMode::Opaque);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

// One polygon of many corners: tinyobjloader's ear clipping is quadratic (60,000 corners took
// 16 s), so beyond the limit the face is refused by its line before it is triangulated; a polygon
// at the limit (a circle of 4096 corners) loads as 4094 triangles.
std::string circleFace(size_t corners) {
  std::string text = "# a circle\n";
  for (size_t i = 0; i < corners; ++i) {
    const double angle = 6.283185307179586 * double(i) / double(corners);
    text += "v " + std::to_string(std::cos(angle)) + " 0 " + std::to_string(std::sin(angle)) + "\n";
  }
  text += "f";
  for (size_t i = 1; i <= corners; ++i) text += " " + std::to_string(i);
  return text + "\n";
}

TEST(UntrustedObj, RefusesAPolygonOfMoreCornersThanItTriangulatesInTime) {
  const fs::path dir = scratch("polygon");
  const fs::path atLimit = testing::writeFile(dir / "limit.obj", circleFace(4096));
  EXPECT_EQ(testing::loadAsWritten(atLimit.string()).triangleCount(), 4094u);
  const fs::path beyond = testing::writeFile(dir / "beyond.obj", circleFace(100000));
  EXPECT_EQ(refusal(beyond), beyond.string() +
                                 ": line 100002: a face of 100000 corners; penumbra takes polygons "
                                 "of at most 4096 (triangulating it would take quadratic time)");
}

// A quad with normals and texture coordinates drawn by `nodes` with material 0 (`material`, the
// JSON object, textured by tex.png); `poison` writes `value` into component 0 of vertex 2 of
// POSITION, NORMAL or TEXCOORD_0 (accessors 0, 2, 3).
struct QuadFile {
  std::string material = R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})";
  std::string nodes = R"([{"mesh":0}])";
  std::string poison;  // "", "POSITION", "NORMAL" or "TEXCOORD_0"
  float value = 0.0f;
};

QuadFile poisoned(std::string attribute, float value) {
  QuadFile q;
  q.poison = std::move(attribute);
  q.value = value;
  return q;
}

QuadFile withMaterial(std::string material) {
  QuadFile q;
  q.material = std::move(material);
  return q;
}

fs::path writeQuad(const fs::path& dir, const QuadFile& q) {
  const std::vector<float> positions{-0.5f, 0, -0.5f, -0.5f, 0, 0.5f,
                                     0.5f,  0, 0.5f,  0.5f,  0, -0.5f};
  const std::vector<uint16_t> indices{0, 1, 2, 0, 2, 3};
  const std::vector<float> normals{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::vector<float> texcoords{0, 0, 0, 1, 1, 1, 1, 0};
  std::vector<uint8_t> buffer(48 + 12 + 48 + 32);
  std::memcpy(buffer.data(), positions.data(), 48);
  std::memcpy(buffer.data() + 48, indices.data(), 12);
  std::memcpy(buffer.data() + 60, normals.data(), 48);
  std::memcpy(buffer.data() + 108, texcoords.data(), 32);
  const size_t poisoned = q.poison == "POSITION" ? 2 * 12
                          : q.poison == "NORMAL" ? 60 + 2 * 12
                                                 : 108 + 2 * 8;
  if (!q.poison.empty()) std::memcpy(buffer.data() + poisoned, &q.value, 4);
  const uint8_t rgb[12] = {255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255};
  writeEncodedColorPng(2, 2, rgb, dir / "tex.png");
  return testing::writeFile(
      dir / "quad.gltf",
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + q.nodes +
          R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":2,"TEXCOORD_0":3},)"
          R"("indices":1,"material":0}]}],"materials":[)" +
          q.material +
          R"(],"textures":[{"source":0}],"images":[{"uri":"tex.png"}],)"
          R"("buffers":[{"byteLength":140,"uri":"data:application/octet-stream;base64,)" +
          testing::base64(buffer) +
          R"("}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},)"
          R"({"buffer":0,"byteOffset":48,"byteLength":12},{"buffer":0,"byteOffset":60,)"
          R"("byteLength":48},{"buffer":0,"byteOffset":108,"byteLength":32}],"accessors":[)"
          R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",)"
          R"("min":[-0.5,0,-0.5],"max":[0.5,0,0.5]},)"
          R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"},)"
          R"({"bufferView":2,"componentType":5126,"count":4,"type":"VEC3"},)"
          R"({"bufferView":3,"componentType":5126,"count":4,"type":"VEC2"}]})");
}

// A node transform that overflows float (1e39) became an infinite transform: refused by node.
TEST(UntrustedGltf, RefusesANodeTransformBeyondSinglePrecision) {
  QuadFile q;
  q.nodes = R"([{"mesh":0,"translation":[1e39,0,0]}])";
  const fs::path file = writeQuad(scratch("node_transform"), q);
  EXPECT_NE(refusal(file).find("node 0's translation is not finite in single precision"),
            std::string::npos)
      << refusal(file);
}

TEST(UntrustedGltf, LoadsTheGeneratedQuad) {
  const Scene s = testing::loadAsWritten(writeQuad(scratch("quad"), {}).string());
  EXPECT_EQ(s.triangleCount(), 2u);
  EXPECT_EQ(s.textures.size(), 1u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(UntrustedGltf, RefusesANonFiniteValueInAnAccessorItUsesNamingTheAccessorAndElement) {
  const fs::path dir = scratch("accessors");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const fs::path position = writeQuad(dir, poisoned("POSITION", nan));
  EXPECT_EQ(refusal(position), position.string() +
                                   ": mesh 0 primitive 0 POSITION (accessor 0) element 2 is not "
                                   "finite (nan, 0, 0.5)");
  // A non-finite normal was replaced by its triangles' normal; glTF allows none (§3.6.2.4).
  const fs::path normal = writeQuad(dir, poisoned("NORMAL", -inf));
  EXPECT_EQ(refusal(normal), normal.string() +
                                 ": mesh 0 primitive 0 NORMAL (accessor 2) element 2 is not "
                                 "finite (-inf, 1, 0)");
  const fs::path texcoord = writeQuad(dir, poisoned("TEXCOORD_0", inf));
  EXPECT_EQ(refusal(texcoord), texcoord.string() +
                                   ": mesh 0 primitive 0 TEXCOORD_0 (accessor 3) element 2 is "
                                   "not finite (inf, 1)");
}

TEST(UntrustedGltf, RefusesAMaterialFactorBeyondSinglePrecisionNamingTheMaterialAndValue) {
  const fs::path dir = scratch("factors");
  // JSON has no NaN, and the parser refuses a number beyond double (1e400) in one line; 1e39 is
  // a double that becomes infinite as float: a cutoff that masked everything, a colour clamped to
  // 1 without a word.
  const fs::path colour =
      writeQuad(dir, withMaterial(R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1e39,1,1]}})"));
  EXPECT_EQ(refusal(colour), colour.string() +
                                 ": material 0's baseColorFactor must be 4 numbers within single "
                                 "precision (it is [1, 1e+39, 1, 1])");
  // Refused in OPAQUE too, where glTF ignores the cutoff.
  const fs::path cutoff = writeQuad(dir, withMaterial(R"({"alphaCutoff":-1e39})"));
  EXPECT_EQ(refusal(cutoff),
            cutoff.string() + ": material 0's alphaCutoff -1e+39 is beyond single precision");
  const fs::path overflow = writeQuad(dir, withMaterial(R"({"alphaCutoff":1e400})"));
  EXPECT_EQ(refusal(overflow), overflow.string() +
                                   ": not a valid glTF 2.0 file: [json.exception.out_of_range.406] "
                                   "number overflow parsing '1e400'");
}

TEST(UntrustedGltf, WarnsOncePerMaterialThatBlendIsDrawnAsAMask) {
  // Two nodes draw the quad: the material is applied twice, and warned about once.
  QuadFile quad = withMaterial(
      R"({"name":"glass","alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.25]}})");
  quad.nodes = R"([{"mesh":0,"children":[1]},{"mesh":0,"translation":[0,1,0]}])";
  const fs::path file = writeQuad(scratch("blend"), quad);
  const Scene s = testing::loadAsWritten(file.string());
  ASSERT_EQ(s.meshes.size(), 2u);
  for (const Mesh& m : s.meshes) EXPECT_EQ(m.alphaMode, AlphaMode::Blend);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], file.string() +
                               ": material 0 ('glass') is BLEND (baseColorFactor alpha 0.250000): "
                               "its shadow lets through 1 - alpha (the light pass covers a "
                               "dithered alpha share of the shadow map's texels, which filtering "
                               "averages; the ray-traced truth attenuates exactly; techniques "
                               "that cannot carry it draw a mask at 0.5, as the camera does)");
}

}  // namespace
}  // namespace penumbra
