// glTF animation and skinning: the waving-bars fixture (scripts/make-waving-bars) posed at its
// keyframes against positions computed by hand from its description, each interpolation mode
// against its closed form, and malformed animations refused with the fault named.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "load_as_written.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "penumbra/scene_animation.h"
#include "scene_fixtures.h"

namespace penumbra {
namespace {

const std::string kBars = PENUMBRA_TEST_DATA_DIR "/waving_bars.gltf";

// The fixture as its script describes it.
constexpr int kSides = 16;
constexpr float kBarRadius = 0.15f;
constexpr size_t kGroundMesh = 0, kBoxMesh = 1, kFirstBarMesh = 2;  // the scene's node order
const glm::vec3 kBar0Base{-5.0f, 0.0f, -5.0f};
const float kBar0Angle = glm::radians(8.0f);  // (-1)^0 (8 + 1.5 * 0) degrees
// Vertex `side` of ring `ring` (rings at heights 0, 0.5, ..., 3).
size_t barVertex(int ring, int side) {
  return size_t(ring * kSides + side);
}

// Positions are sums of a few products of floats of magnitude up to 6: a few float ulps of that.
constexpr float kPositionTolerance = 1e-5f * 8.0f;

glm::vec3 turnAboutZ(glm::vec3 v, float radians) {
  return {v.x * std::cos(radians) - v.y * std::sin(radians),
          v.x * std::sin(radians) + v.y * std::cos(radians), v.z};
}

void expectNear(glm::vec3 actual, glm::vec3 expected, const std::string& what) {
  EXPECT_NEAR(actual.x, expected.x, kPositionTolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, kPositionTolerance) << what;
  EXPECT_NEAR(actual.z, expected.z, kPositionTolerance) << what;
}

TEST(SceneAnimation, TheFixtureKeepsItsClipSkinsAndMovingMeshes) {
  const Scene scene = testing::loadAsWritten(kBars);
  EXPECT_TRUE(scene.animation.moves());
  EXPECT_EQ(scene.animation.clip, "wave");
  EXPECT_FLOAT_EQ(scene.animation.duration, 2.0f);
  EXPECT_EQ(scene.animation.skins.size(), 25u);
  // 25 bars and the box move; the ground does not.
  ASSERT_EQ(scene.animation.meshes.size(), 26u);
  for (const PosedMesh& posed : scene.animation.meshes) EXPECT_NE(posed.mesh, kGroundMesh);
}

// Bar 0's chain: joint 1 at height 1 and joint 2 at height 2 above its base, each turned by the
// bar's angle at t = 1 s (LINEAR keys 0, angle, 0 at 0, 1, 2 s). The tip ring follows joint 2
// alone: a rigid chain. The ring at height 1 follows joints 0 and 1 half each: the average of
// where each would carry it (linear blend skinning).
TEST(SceneAnimation, ASkinnedBarMatchesHandComputedPositionsAtItsKeyframes) {
  Scene scene = testing::loadAsWritten(kBars);
  const auto bar = [&]() -> const Mesh& { return scene.meshes[kFirstBarMesh]; };
  const glm::vec3 tipBind{kBarRadius, 3.0f, 0.0f}, middleBind{kBarRadius, 1.0f, 0.0f};
  const auto expectPose = [&](float angle, const std::string& when) {
    const glm::vec3 joint1 = kBar0Base + glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 joint2 = joint1 + turnAboutZ({0.0f, 1.0f, 0.0f}, angle);
    const glm::vec3 tip = joint2 + turnAboutZ(tipBind - glm::vec3(0.0f, 2.0f, 0.0f), 2.0f * angle);
    const glm::vec3 middle =
        0.5f * (kBar0Base + middleBind) +
        0.5f * (joint1 + turnAboutZ(middleBind - glm::vec3(0.0f, 1.0f, 0.0f), angle));
    expectNear(bar().vertices[barVertex(6, 0)].position, tip, "tip, " + when);
    expectNear(bar().vertices[barVertex(2, 0)].position, middle, "middle ring, " + when);
    // The tip ring's normal turns with joint 2.
    expectNear(bar().vertices[barVertex(6, 0)].normal, turnAboutZ({1.0f, 0.0f, 0.0f}, 2.0f * angle),
               "tip normal, " + when);
  };
  expectPose(0.0f, "as loaded");  // the clip's start: upright
  poseScene(scene, 1.0f);
  expectPose(kBar0Angle, "at 1 s");
  poseScene(scene, 0.5f);
  expectPose(0.5f * kBar0Angle, "at 0.5 s");  // slerp halfway
  poseScene(scene, 2.0f);
  expectPose(0.0f, "at 2 s");
  poseScene(scene, 7.0f);
  expectPose(0.0f, "after the last key");  // held at the last key
}

// The box is drawn by a node whose translation slides from x = -5 to 5 at z = 5.5 over 2 s; it has
// no normals, so each triangle has its own three vertices and a normal of its own.
TEST(SceneAnimation, ARigidNodeAnimationMovesItsFlatShadedMesh) {
  Scene scene = testing::loadAsWritten(kBars);
  const glm::vec3 corner{-0.4f, 0.0f, -0.4f};  // vertex 0: the first triangle's first corner
  expectNear(scene.meshes[kBoxMesh].vertices[0].position, corner + glm::vec3(-5.0f, 0.0f, 5.5f),
             "box at 0 s");
  poseScene(scene, 1.0f);
  expectNear(scene.meshes[kBoxMesh].vertices[0].position, corner + glm::vec3(0.0f, 0.0f, 5.5f),
             "box at 1 s");
  poseScene(scene, 1.5f);
  expectNear(scene.meshes[kBoxMesh].vertices[0].position, corner + glm::vec3(2.5f, 0.0f, 5.5f),
             "box at 1.5 s");
  // The first triangle (corners 0, 2, 3) faces -z.
  for (int k = 0; k < 3; ++k) {
    expectNear(scene.meshes[kBoxMesh].vertices[size_t(k)].normal, {0.0f, 0.0f, -1.0f},
               "first triangle's normal");
  }
}

AnimationChannel channel(AnimatedProperty property, KeyInterpolation interpolation,
                         std::vector<float> times, std::vector<glm::vec4> values) {
  AnimationChannel c;
  c.property = property;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.values = std::move(values);
  return c;
}

TEST(SceneAnimation, ChannelsInterpolateAsGltfDefines) {
  const glm::vec4 a{1.0f, 2.0f, 3.0f, 0.0f}, b{5.0f, 6.0f, 11.0f, 0.0f};
  const AnimationChannel step =
      channel(AnimatedProperty::Translation, KeyInterpolation::Step, {1.0f, 2.0f}, {a, b});
  EXPECT_EQ(sampleChannel(step, 0.0f), a);  // before the first key: held
  EXPECT_EQ(sampleChannel(step, 1.99f), a);
  EXPECT_EQ(sampleChannel(step, 2.0f), b);
  const AnimationChannel linear =
      channel(AnimatedProperty::Scale, KeyInterpolation::Linear, {1.0f, 2.0f}, {a, b});
  EXPECT_EQ(sampleChannel(linear, 1.25f), glm::vec4(2.0f, 3.0f, 5.0f, 0.0f));
  EXPECT_EQ(sampleChannel(linear, 9.0f), b);  // after the last: held
  // A rotation a quarter turn about y, halfway: an eighth of a turn (slerp, not a normalised
  // average, which would agree only at the midpoint: checked a quarter of the way too).
  const float s = std::sin(glm::quarter_pi<float>() / 2.0f),
              c = std::cos(glm::quarter_pi<float>() / 2.0f);
  const AnimationChannel turn =
      channel(AnimatedProperty::Rotation, KeyInterpolation::Linear, {0.0f, 1.0f},
              {{0.0f, 0.0f, 0.0f, 1.0f}, {0.0f, std::sqrt(0.5f), 0.0f, std::sqrt(0.5f)}});
  const glm::vec4 half = sampleChannel(turn, 0.5f);
  EXPECT_NEAR(half.y, s, 1e-6f);
  EXPECT_NEAR(half.w, c, 1e-6f);
  const glm::vec4 quarter = sampleChannel(turn, 0.25f);
  const float angle = glm::half_pi<float>() * 0.25f;
  EXPECT_NEAR(quarter.y, std::sin(angle / 2.0f), 1e-6f);
  EXPECT_NEAR(quarter.w, std::cos(angle / 2.0f), 1e-6f);
  // CUBICSPLINE over [0, 2], halfway (s = 0.5): the Hermite basis gives
  // 0.5 v0 + 0.125 * 2 * b0 + 0.5 v1 - 0.125 * 2 * a1 (glTF 2.0 Appendix C).
  const glm::vec4 v0{0.0f}, b0{1.0f, 0.0f, 0.0f, 0.0f}, a1{0.0f, 2.0f, 0.0f, 0.0f},
      v1{1.0f, 1.0f, 1.0f, 0.0f}, unused{9.0f};
  const AnimationChannel cubic =
      channel(AnimatedProperty::Translation, KeyInterpolation::CubicSpline, {0.0f, 2.0f},
              {unused, v0, b0, a1, v1, unused});
  const glm::vec4 mid = sampleChannel(cubic, 1.0f);
  EXPECT_NEAR(mid.x, 0.75f, 1e-6f);
  EXPECT_NEAR(mid.y, 0.0f, 1e-6f);
  EXPECT_NEAR(mid.z, 0.5f, 1e-6f);
  EXPECT_EQ(sampleChannel(cubic, 2.0f), v1);
  // A CUBICSPLINE rotation with zero tangents, halfway: the keys' average renormalised, which for
  // a quarter turn is the eighth turn.
  const glm::vec4 zero{0.0f}, still{0.0f, 0.0f, 0.0f, 1.0f},
      quarterTurn{0.0f, std::sqrt(0.5f), 0.0f, std::sqrt(0.5f)};
  const AnimationChannel cubicTurn =
      channel(AnimatedProperty::Rotation, KeyInterpolation::CubicSpline, {0.0f, 1.0f},
              {zero, still, zero, zero, quarterTurn, zero});
  const glm::vec4 eighth = sampleChannel(cubicTurn, 0.5f);
  EXPECT_NEAR(eighth.y, s, 1e-6f);
  EXPECT_NEAR(eighth.w, c, 1e-6f);
}

// Appends a buffer of these floats to the document with its view and a `type` accessor over it;
// returns the accessor's index.
int addFloats(nlohmann::json& d, const std::vector<float>& values, const std::string& type,
              int components) {
  std::vector<uint8_t> bytes(values.size() * sizeof(float));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  d["buffers"].push_back(
      {{"byteLength", bytes.size()},
       {"uri", "data:application/octet-stream;base64," + testing::base64(bytes)}});
  d["bufferViews"].push_back(
      {{"buffer", d["buffers"].size() - 1}, {"byteOffset", 0}, {"byteLength", bytes.size()}});
  d["accessors"].push_back({{"bufferView", d["bufferViews"].size() - 1},
                            {"componentType", 5126},
                            {"count", values.size() / size_t(components)},
                            {"type", type}});
  return int(d["accessors"].size()) - 1;
}

// The fixture's JSON changed by `edit`, written beside the test's other files.
std::filesystem::path editedBars(const std::function<void(nlohmann::json&)>& edit) {
  std::ifstream in(kBars);
  nlohmann::json document = nlohmann::json::parse(in);
  edit(document);
  // Named after the test and the process: ctest runs tests as processes side by side.
  static int edits = 0;
  const std::filesystem::path path =
      std::filesystem::path(::testing::TempDir()) /
      ("penumbra_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
       "_" + std::to_string(getpid()) + "_" + std::to_string(edits++) + ".gltf");
  std::ofstream(path) << document.dump();
  return path;
}

void expectRefused(const std::function<void(nlohmann::json&)>& edit, const std::string& fault,
                   SceneLoadOptions options = {}) {
  const std::filesystem::path path = editedBars(edit);
  try {
    testing::loadAsWritten(path.string(), options);
    ADD_FAILURE() << "loaded; expected a refusal naming '" << fault << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fault), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(SceneAnimation, MalformedAnimationsAndSkinsAreRefusedWithTheFault) {
  // Times that go back: an accessor over the weights (1, 0, 0 as floats).
  expectRefused(
      [](nlohmann::json& d) {
        nlohmann::json times =
            d["accessors"][d["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"].get<int>()];
        times["type"] = "SCALAR";
        times["count"] = 3;
        times.erase("min");
        times.erase("max");
        d["accessors"].push_back(times);
        d["animations"][0]["samplers"][0]["input"] = d["accessors"].size() - 1;
      },
      "times must increase strictly (key 1 at 0.000000 s follows 1.000000 s)");
  expectRefused(
      [](nlohmann::json& d) { d["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE"; },
      "output has 3 values for 3 keys (CUBICSPLINE needs 9)");
  expectRefused(
      [](nlohmann::json& d) {
        d["animations"][0]["samplers"][0]["input"] = d["animations"][0]["samplers"][0]["output"];
      },
      "input (accessor");
  expectRefused(
      [](nlohmann::json& d) {
        d["nodes"][1].erase("translation");
        d["nodes"][1]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
      },
      "animates node 1, which is given by a matrix");
  expectRefused([](nlohmann::json& d) { d["animations"][0]["channels"][0]["sampler"] = 999; },
                "channel 0 names sampler 999");
  expectRefused([](nlohmann::json& d) { d["skins"][0]["joints"][2] = 999; },
                "skin 0's joint node 999 is not a node of the scene drawn");
  // Two joints where the vertices name three: the inverse bind matrices disagree first.
  expectRefused([](nlohmann::json& d) { d["skins"][0]["joints"].erase(2); },
                "skin 0 has 3 inverse bind matrices for 2 joints");
  expectRefused(
      [](nlohmann::json& d) {
        d["skins"][0]["joints"].erase(2);
        d["skins"][0].erase("inverseBindMatrices");
      },
      "names joint 2 of skin 0, which has 2");
  // A pose far beyond single precision's reach (the box slides to +-3e38): refused at load, not a
  // blank frame later.
  expectRefused(
      [](nlohmann::json& d) {
        d["animations"][0]["samplers"][0]["output"] =
            addFloats(d, {-5.0f, 0.0f, 5.5f, 3e38f, 0.0f, 5.5f, -3e38f, 0.0f, 5.5f}, "VEC3", 3);
      },
      "s of its animation 'wave' the moving meshes' extent is not finite");
  // Ten million keys are charged before they are read: refused by the memory budget.
  SceneLoadOptions small;
  small.maxMemoryBytes = uint64_t(64) << 20;
  expectRefused(
      [](nlohmann::json& d) {
        d["accessors"][d["animations"][0]["samplers"][0]["input"].get<int>()]["count"] = 10000000;
      },
      "of host memory", small);
}

// A node whose scale turns negative mirrors its mesh: the winding turns back with it, so the box's
// faces keep facing out (glTF 2.0 §3.7.4).
TEST(SceneAnimation, AMirroringScaleTurnsTheWindingBack) {
  const std::filesystem::path path = editedBars([](nlohmann::json& d) {
    const int times = addFloats(d, {0.0f, 1.0f}, "SCALAR", 1);
    const int scales = addFloats(d, {1.0f, 1.0f, 1.0f, -1.0f, 1.0f, 1.0f}, "VEC3", 3);
    d["animations"][0]["samplers"].push_back(
        {{"input", times}, {"output", scales}, {"interpolation", "STEP"}});
    d["animations"][0]["channels"].push_back(
        {{"sampler", d["animations"][0]["samplers"].size() - 1},
         {"target", {{"node", 1}, {"path", "scale"}}}});
  });
  Scene scene = testing::loadAsWritten(path.string());
  std::filesystem::remove(path);
  const auto outward = [&](const std::string& when) {
    // Every flat-shaded triangle's normal points away from the box's centre.
    const Mesh& box = scene.meshes[kBoxMesh];
    glm::vec3 centre(0.0f);
    for (const Vertex& v : box.vertices) centre += v.position / float(box.vertices.size());
    for (size_t t = 0; t + 2 < box.indices.size(); t += 3) {
      const Vertex& a = box.vertices[box.indices[t]];
      const Vertex& b = box.vertices[box.indices[t + 1]];
      const Vertex& c = box.vertices[box.indices[t + 2]];
      const glm::vec3 wound = glm::cross(b.position - a.position, c.position - a.position);
      const glm::vec3 middle = (a.position + b.position + c.position) / 3.0f;
      EXPECT_GT(glm::dot(wound, middle - centre), 0.0f) << "triangle " << t / 3 << ", " << when;
      EXPECT_GT(glm::dot(a.normal, middle - centre), 0.0f) << "triangle " << t / 3 << ", " << when;
    }
  };
  outward("at 0 s");
  const std::vector<uint32_t> upright = scene.meshes[kBoxMesh].indices;
  poseScene(scene, 1.5f);  // mirrored in x
  EXPECT_NE(scene.meshes[kBoxMesh].indices, upright);
  outward("mirrored at 1.5 s");
  poseScene(scene, 0.5f);
  EXPECT_EQ(scene.meshes[kBoxMesh].indices, upright);
  outward("upright again at 0.5 s");
}

}  // namespace
}  // namespace penumbra
