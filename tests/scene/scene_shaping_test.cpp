// What loadScene does to a scene file for a first picture (docs/scenes.md, "Real models"): the
// framing camera at the frame's aspect, the ground under a lone model, enclosures and unlit
// meshes out of the shadows, a file camera only when it sees the whole model, the default point
// light above the model.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "load_as_written.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scene_fixtures.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

fs::path scratchFolder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("penumbra_shaping_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Axis-aligned boxes as OBJ, each its own material (so its own mesh); faces wound outwards.
struct ObjBoxes {
  std::ostringstream obj;
  std::string mtl;
  int first = 1;
  int count = 0;

  void add(glm::vec3 lo, glm::vec3 hi) {
    const std::string material = "m" + std::to_string(count++);
    mtl += "newmtl " + material + "\nKd 0.8 0.8 0.8\n";
    obj << "usemtl " << material << "\n";
    for (int i = 0; i < 8; ++i) {
      obj << "v " << (i & 1 ? hi.x : lo.x) << " " << (i & 2 ? hi.y : lo.y) << " "
          << (i & 4 ? hi.z : lo.z) << "\n";
    }
    const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                              {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    for (const auto& f : faces) {
      obj << "f " << first + f[0] << " " << first + f[1] << " " << first + f[2] << "\n";
    }
    first += 8;
  }

  fs::path write(const fs::path& dir, const std::string& name) const {
    testing::writeFile(dir / (name + ".mtl"), mtl);
    return testing::writeFile(dir / (name + ".obj"), "mtllib " + name + ".mtl\n" + obj.str());
  }
};

SceneLoadOptions options(GroundMode ground, float aspect = 16.0f / 9.0f) {
  SceneLoadOptions o;
  o.ground = ground;
  o.aspect = aspect;
  return o;
}

// The largest |x| and |y| in normalised device coordinates over the model's vertices.
glm::vec2 projectedExtent(const Scene& scene, float aspect) {
  const glm::mat4 clipFromWorld =
      clipFromView(scene.camera, aspect, scene.viewBounds()) * viewFromWorld(scene.camera);
  glm::vec2 extent(0.0f);
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.role != MeshRole::Model) continue;
    for (const Vertex& v : mesh.vertices) {
      const glm::vec4 clip = clipFromWorld * glm::vec4(v.position, 1.0f);
      EXPECT_GT(clip.w, 0.0f);
      EXPECT_LE(std::abs(clip.z), clip.w) << "clipped by the near or far plane";
      extent = glm::max(extent, glm::abs(glm::vec2(clip) / clip.w));
    }
  }
  return extent;
}

// The framing rule: the binding axis at exactly kFramingFill, the other inside it. 1e-4: the
// distance and projection are float arithmetic on values of order one (relative error ~1e-6).
TEST(SceneShaping, TheFramingCameraFillsTheStatedShareOfTheFrameAtItsAspect) {
  const fs::path dir = scratchFolder("framing");
  struct Case {
    const char* name;
    glm::vec3 lo, hi;
    float aspect;
    bool widthBinds;
  };
  for (const Case& c :
       {Case{"tall", {-0.5f, 0.0f, -0.5f}, {0.5f, 10.0f, 0.5f}, 16.0f / 9.0f, false},
        Case{"wide", {-10.0f, 0.0f, -0.5f}, {10.0f, 1.0f, 0.5f}, 16.0f / 9.0f, true},
        Case{"wide_in_portrait", {-2.0f, 0.0f, -0.5f}, {2.0f, 1.0f, 0.5f}, 9.0f / 16.0f, true},
        Case{"tiny", {-5e-4f, 0.0f, -5e-4f}, {5e-4f, 1e-3f, 5e-4f}, 16.0f / 9.0f, false}}) {
    ObjBoxes boxes;
    boxes.add(c.lo, c.hi);
    const Scene s =
        loadScene(boxes.write(dir, c.name).string(), options(GroundMode::Off, c.aspect));
    const glm::vec2 extent = projectedExtent(s, c.aspect);
    const float binding = c.widthBinds ? extent.x : extent.y;
    const float other = c.widthBinds ? extent.y : extent.x;
    EXPECT_NEAR(binding, kFramingFill, 1e-4f) << c.name;
    EXPECT_LE(other, kFramingFill + 1e-4f) << c.name;
  }
  fs::remove_all(dir);
}

TEST(SceneShaping, AGroundLiesUnderALoneModelAndNotUnderOneWithAFloor) {
  const fs::path dir = scratchFolder("ground");
  ObjBoxes lone;
  lone.add({-0.5f, 1.0f, -0.5f}, {0.5f, 2.0f, 0.5f});
  const Scene s = loadScene(lone.write(dir, "lone").string(), options(GroundMode::Auto));
  ASSERT_EQ(s.meshes.size(), 2u);
  const Mesh& ground = s.meshes.back();
  EXPECT_EQ(ground.role, MeshRole::Ground);
  for (const Vertex& v : ground.vertices) {
    EXPECT_LT(v.position.y, 1.0f);
    EXPECT_GT(v.position.y, 1.0f - 1e-2f);  // just under the model, not far below it
    EXPECT_EQ(v.normal, glm::vec3(0.0f, 1.0f, 0.0f));
  }
  // The default light's shadow of every corner of the model lands on the ground.
  const Bounds g = s.bounds();
  for (const Vertex& v : s.meshes[0].vertices) {
    const glm::vec3 d = s.light.direction;
    const glm::vec3 onGround = v.position + d * ((g.min.y - v.position.y) / d.y);
    EXPECT_GT(onGround.x, g.min.x);
    EXPECT_LT(onGround.x, g.max.x);
    EXPECT_GT(onGround.z, g.min.z);
    EXPECT_LT(onGround.z, g.max.z);
  }
  EXPECT_EQ(s.modelBounds().min.y, 1.0f);  // framing looks at the model, not the ground
  EXPECT_FALSE(s.notes.empty());

  EXPECT_EQ(loadScene(lone.write(dir, "lone").string(), options(GroundMode::Off)).meshes.size(),
            1u);

  ObjBoxes onFloor;
  onFloor.add({-5.0f, -0.1f, -5.0f}, {5.0f, 0.0f, 5.0f});
  onFloor.add({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f});
  const fs::path floorFile = onFloor.write(dir, "floor");
  EXPECT_EQ(loadScene(floorFile.string(), options(GroundMode::Auto)).meshes.size(), 2u);
  EXPECT_EQ(loadScene(floorFile.string(), options(GroundMode::On)).meshes.size(), 3u);
  fs::remove_all(dir);
}

// A closed shell in two pieces (walls, roof) far around a block on a floor: the sky dome's case.
ObjBoxes domeScene() {
  ObjBoxes boxes;
  boxes.add({-4.0f, -0.2f, -4.0f}, {4.0f, 0.0f, 4.0f});        // floor
  boxes.add({-0.5f, 0.0f, -0.5f}, {0.5f, 1.5f, 0.5f});         // block
  boxes.add({-20.0f, -1.0f, -20.0f}, {-19.0f, 20.0f, 20.0f});  // walls
  boxes.add({19.0f, -1.0f, -20.0f}, {20.0f, 20.0f, 20.0f});
  boxes.add({-20.0f, -1.0f, -20.0f}, {20.0f, 20.0f, -19.0f});
  boxes.add({-20.0f, -1.0f, 19.0f}, {20.0f, 20.0f, 20.0f});
  boxes.add({-20.0f, 19.0f, -20.0f}, {20.0f, 20.0f, 20.0f});  // roof
  return boxes;
}

TEST(SceneShaping, GeometryEnclosingTheModelCastsNoShadowUnlessAllCast) {
  const fs::path dir = scratchFolder("dome");
  const fs::path file = domeScene().write(dir, "dome");
  const Scene s = loadScene(file.string(), options(GroundMode::Auto));
  ASSERT_EQ(s.meshes.size(), 7u);  // no ground: the floor is there
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    const bool shell = m >= 2;
    EXPECT_EQ(s.meshes[m].role, shell ? MeshRole::Enclosure : MeshRole::Model) << m;
    EXPECT_EQ(s.meshes[m].castsShadow, !shell) << m;
  }
  EXPECT_EQ(s.modelBounds().max.y, 1.5f);
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("5 meshes enclose"), std::string::npos) << s.notes[0];

  SceneLoadOptions all = options(GroundMode::Auto);
  all.casters = CasterMode::All;
  for (const Mesh& mesh : loadScene(file.string(), all).meshes) EXPECT_TRUE(mesh.castsShadow);

  // The same floor and block without the shell: the floor hugs the bounds' bottom only.
  ObjBoxes open;
  open.add({-4.0f, -0.2f, -4.0f}, {4.0f, 0.0f, 4.0f});
  open.add({-0.5f, 0.0f, -0.5f}, {0.5f, 1.5f, 0.5f});
  for (const Mesh& mesh :
       loadScene(open.write(dir, "open").string(), options(GroundMode::Auto)).meshes) {
    EXPECT_EQ(mesh.role, MeshRole::Model);
    EXPECT_TRUE(mesh.castsShadow);
  }
  fs::remove_all(dir);
}

// A house: four walls and a roof, each its own mesh, round a floor plate and nothing else. They
// reach the bounds' sides and top, close the sky and face the middle as a skybox does, but
// nothing stands inside: the house is the model, drawn, framed and casting as written.
TEST(SceneShaping, AHouseOverABareFloorIsTheModelNotAnEnclosure) {
  const fs::path dir = scratchFolder("house");
  ObjBoxes house;
  house.add({-4.8f, -0.2f, -4.8f}, {4.8f, 0.0f, 4.8f});   // floor plate
  house.add({-5.0f, -0.2f, -5.0f}, {-4.8f, 3.0f, 5.0f});  // walls
  house.add({4.8f, -0.2f, -5.0f}, {5.0f, 3.0f, 5.0f});
  house.add({-5.0f, -0.2f, -5.0f}, {5.0f, 3.0f, -4.8f});
  house.add({-5.0f, -0.2f, 4.8f}, {5.0f, 3.0f, 5.0f});
  house.add({-5.0f, 3.0f, -5.0f}, {5.0f, 3.2f, 5.0f});  // roof
  const fs::path file = house.write(dir, "house");
  const Scene s = loadScene(file.string(), options(GroundMode::Off));
  ASSERT_EQ(s.meshes.size(), 6u);
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    EXPECT_EQ(s.meshes[m].role, MeshRole::Model) << m;
    EXPECT_TRUE(s.meshes[m].castsShadow) << m;
    EXPECT_TRUE(s.meshes[m].doubleSided) << m;  // not turned inwards and culled from outside
  }
  for (const std::string& note : s.notes) ADD_FAILURE() << note;
  fs::remove_all(dir);
}

// --casters all keeps an enclosure the model, as the file has it, and says what it would have
// been.
TEST(SceneShaping, AllCastersLeaveAnEnclosureAsWrittenAndSaySo) {
  const fs::path dir = scratchFolder("dome_all");
  SceneLoadOptions all = options(GroundMode::Off);
  all.casters = CasterMode::All;
  const Scene s = loadScene(domeScene().write(dir, "dome").string(), all);
  for (const Mesh& mesh : s.meshes) {
    EXPECT_EQ(mesh.role, MeshRole::Model);
    EXPECT_TRUE(mesh.castsShadow);
    EXPECT_TRUE(mesh.doubleSided);
  }
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("5 meshes seem to enclose"), std::string::npos) << s.notes[0];
  fs::remove_all(dir);
}

// A unit box with no floor inside a skybox a thousand times its radius: the near plane and the
// light's map come from the box and the ground added under it, the far plane reaches the sky.
TEST(SceneShaping, ASkyboxMovesNeitherTheNearPlaneNorTheLightsFit) {
  const fs::path dir = scratchFolder("skybox");
  ObjBoxes boxes;
  boxes.add({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f});
  const float sky = 900.0f;  // the box's radius is 0.87
  boxes.add({-sky, -sky, -sky}, {-sky + 10.0f, sky, sky});
  boxes.add({sky - 10.0f, -sky, -sky}, {sky, sky, sky});
  boxes.add({-sky, -sky, -sky}, {sky, sky, -sky + 10.0f});
  boxes.add({-sky, -sky, sky - 10.0f}, {sky, sky, sky});
  boxes.add({-sky, sky - 10.0f, -sky}, {sky, sky, sky});
  const Scene s = loadScene(boxes.write(dir, "skybox").string(), options(GroundMode::Auto));
  ASSERT_EQ(s.meshes.size(), 7u);  // the box, five sky pieces, a ground
  for (size_t m = 1; m < 6; ++m) EXPECT_EQ(s.meshes[m].role, MeshRole::Enclosure) << m;
  EXPECT_EQ(s.meshes[6].role, MeshRole::Ground);

  const float modelRadius = s.modelBounds().radius();
  const Bounds shadowed = s.shadowBounds();
  EXPECT_LT(shadowed.radius(), 3.0f * modelRadius);  // the box and its ground
  EXPECT_EQ(shadowed.min.x, s.meshes[6].vertices[0].position.x);
  // The framing camera sees every vertex of the box in front of the near plane (projectedExtent
  // checks each against the clip volume), and the far plane reaches past the sky's far corner.
  const glm::vec2 extent = projectedExtent(s, 16.0f / 9.0f);
  EXPECT_NEAR(std::max(extent.x, extent.y), kFramingFill, 1e-3f);
  EXPECT_LE(cameraNear(s.viewBounds()), 0.1f * modelRadius);
  EXPECT_GT(cameraFar(s.camera, s.viewBounds()), glm::length(glm::vec3(-sky) - s.camera.position));
  // The directional light's map spans the box and its ground, not the sky: a texel is a
  // thousandth of the model's size at 1024 texels, not the sky's.
  const LightView light = fitLightView(s);
  EXPECT_LE(light.texelWorldSize(1024) * 1024.0f, 2.0f * shadowed.radius() * 1.0001f);
  EXPECT_LT(light.texelWorldSize(1024), 5.0f * modelRadius / 1024.0f);
  fs::remove_all(dir);
}

// tests/data/dome_city.obj (scripts/make-dome-city): nine buildings on a floor that reaches a
// hemispherical sky dome in eight pieces, faces inwards — VC.glb's case.
TEST(SceneShaping, AHemisphericalDomeOverACityIsAnEnclosure) {
  const Scene s = loadScene(PENUMBRA_TEST_DATA_DIR "/dome_city.obj", options(GroundMode::Auto));
  ASSERT_EQ(s.meshes.size(), 18u);  // floor, nine buildings, eight dome pieces; no ground added
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    EXPECT_EQ(s.meshes[m].role, m >= 10 ? MeshRole::Enclosure : MeshRole::Model) << m;
  }
  EXPECT_EQ(s.modelBounds().max.y, 26.0f);  // the tallest building
  // The dome faces the city and is culled from outside, where the framing camera stands.
  EXPECT_GT(glm::length(s.camera.position - glm::vec3(0.0f)), 60.0f);
  for (size_t m = 10; m < s.meshes.size(); ++m) {
    const Mesh& dome = s.meshes[m];
    EXPECT_FALSE(dome.doubleSided) << m;
    for (size_t t = 0; t + 2 < dome.indices.size(); t += 3) {
      const glm::vec3 a = dome.vertices[dome.indices[t]].position;
      const glm::vec3 b = dome.vertices[dome.indices[t + 1]].position;
      const glm::vec3 c = dome.vertices[dome.indices[t + 2]].position;
      ASSERT_LT(glm::dot(glm::cross(b - a, c - a), a + b + c), 0.0f) << m << " " << t;
    }
  }
}

// spider.obj's case: legs reach the bounds' sides and top round a lower body, but the sky shows
// between them: a model, not an enclosure.
TEST(SceneShaping, PartsRoundAModelThatLeaveTheSkyOpenAreNoEnclosure) {
  const fs::path dir = scratchFolder("legs");
  ObjBoxes spider;
  spider.add({-1.0f, 1.0f, -1.0f}, {1.0f, 2.0f, 1.0f});  // body
  for (int leg = 0; leg < 4; ++leg) {
    const float x = leg & 1 ? 4.0f : -5.0f, z = leg & 2 ? 4.0f : -5.0f;
    spider.add({x, 0.0f, z}, {x + 1.0f, 5.0f, z + 1.0f});
  }
  const Scene s = loadScene(spider.write(dir, "spider").string(), options(GroundMode::Off));
  for (const Mesh& mesh : s.meshes) {
    EXPECT_EQ(mesh.role, MeshRole::Model);
    EXPECT_TRUE(mesh.castsShadow);
  }
  fs::remove_all(dir);
}

// The real spider: its legs and body surround its eyes and teeth and close the sky over them,
// but their faces turn sideways, not towards them as a dome's do.
TEST(SceneShaping, TheSpidersBodyAndLegsAreTheModel) {
  const Scene s = loadScene("/usr/share/assimp/models/OBJ/spider.obj", options(GroundMode::Off));
  for (const Mesh& mesh : s.meshes) EXPECT_EQ(mesh.role, MeshRole::Model);
}

TEST(SceneShaping, UnlitMaterialsCastNoShadowUnlessAllCast) {
  const fs::path dir = scratchFolder("unlit");
  const fs::path file = testing::writeFile(
      dir / "unlit.gltf",
      testing::gltfWithMesh(
          {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, R"([{"mesh":0}])", "[0]",
          R"(,"material":0)",
          R"(,"extensionsUsed":["KHR_materials_unlit"],"materials":[{"extensions":{"KHR_materials_unlit":{}}}])"));
  const Scene s = loadScene(file.string(), options(GroundMode::Off));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.meshes[0].unlit);
  EXPECT_FALSE(s.meshes[0].castsShadow);
  SceneLoadOptions all = options(GroundMode::Off);
  all.casters = CasterMode::All;
  EXPECT_TRUE(loadScene(file.string(), all).meshes[0].castsShadow);
  fs::remove_all(dir);
}

// A unit triangle at the origin and a camera on +z with a 17-degree field of view.
fs::path cameraFile(const fs::path& dir, float distance) {
  return testing::writeFile(
      dir / ("camera_" + std::to_string(int(distance)) + ".gltf"),
      testing::gltfWithMesh(
          {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0, 0.5f, 0}}, {0, 1, 2},
          R"([{"mesh":0},{"camera":0,"translation":[0,0,)" + std::to_string(distance) + "]}]",
          "[0,1]", "",
          R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.3,"znear":0.01}}])"));
}

TEST(SceneShaping, AFileCameraIsTheDefaultOnlyWhenItSeesTheWholeModel) {
  const fs::path dir = scratchFolder("cameras");
  const float fileFov = glm::degrees(0.3f);
  // From 20 units the triangle is well inside the frame: the file's camera.
  const Scene far = loadScene(cameraFile(dir, 20.0f).string(), options(GroundMode::Off));
  EXPECT_NEAR(far.camera.verticalFovDegrees, fileFov, 1e-3f);
  EXPECT_TRUE(far.warnings.empty());
  // From 1.5 units it crops the triangle (0.22 units of half height in view): the framing camera.
  const fs::path nearFile = cameraFile(dir, 1.5f);
  const Scene near = loadScene(nearFile.string(), options(GroundMode::Off));
  EXPECT_EQ(near.camera.verticalFovDegrees, 45.0f);
  ASSERT_EQ(near.warnings.size(), 1u);
  EXPECT_NE(near.warnings[0].find("--camera N picks one"), std::string::npos) << near.warnings[0];
  // Named as --camera takes it.
  EXPECT_NE(near.warnings[0].find("(--camera 0 sees "), std::string::npos) << near.warnings[0];
  // Asked for, it is used as it is.
  SceneLoadOptions pick = options(GroundMode::Off);
  pick.camera = 0;
  EXPECT_NEAR(loadScene(nearFile.string(), pick).camera.verticalFovDegrees, fileFov, 1e-3f);
  pick.camera = 3;
  try {
    loadScene(nearFile.string(), pick);
    ADD_FAILURE() << "camera 3 of 1 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--camera 3 is out of range [0, 0]"), std::string::npos)
        << e.what();
  }
  pick.camera = 0;
  EXPECT_THROW(loadScene("backyard", pick), Error);
  fs::remove_all(dir);
}

TEST(SceneShaping, TheDefaultPointLightStandsAboveTheModelNotInsideIt) {
  const fs::path dir = scratchFolder("point");
  ObjBoxes tower;
  tower.add({-0.5f, 0.0f, -0.5f}, {0.5f, 10.0f, 0.5f});
  Scene s = loadScene(tower.write(dir, "tower").string(), options(GroundMode::Auto));
  SceneOverrides point;
  point.lightKind = LightKind::Point;
  applyOverrides(s, point);
  // Halfway towards the sun from the centre is beside the tower at y = 7.2: its top would be
  // dark, lit from below.
  EXPECT_GT(s.light.position.y, 10.0f);
  EXPECT_LT(s.light.position.y, 15.0f);  // not beyond the scene: a quarter radius above the top
  fs::remove_all(dir);
}

}  // namespace
}  // namespace penumbra
