// The built-in scenes, each a papers' test case (figure numbers in the comments; docs/scenes.md).
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "foliage_scene.h"
#include "mesh_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

using scene::addBox;
using scene::addCylinder;
using scene::addGround;
using scene::addSphere;
using scene::makeMesh;

const glm::vec3 kGroundAlbedo(0.75f, 0.72f, 0.65f);
const glm::vec3 kWoodAlbedo(0.62f, 0.45f, 0.3f);
const glm::vec3 kLeafAlbedo(0.35f, 0.6f, 0.3f);
const glm::vec3 kStoneAlbedo(0.7f, 0.7f, 0.75f);

Light directional(glm::vec3 direction) {
  Light light;
  light.kind = LightKind::Directional;
  light.direction = glm::normalize(direction);
  return light;
}

// A scene of that name and description standing on a ground square.
Scene sceneWithGround(std::string name, std::string description, glm::vec3 groundCentre,
                      float groundHalfSize) {
  Scene s;
  s.name = std::move(name);
  s.description = std::move(description);
  Mesh ground = makeMesh(kGroundAlbedo);
  addGround(ground, groundCentre, groundHalfSize);
  s.meshes.push_back(std::move(ground));
  return s;
}

void addTree(Scene& s, glm::vec3 base, float height, float crown) {
  Mesh trunk = makeMesh(kWoodAlbedo);
  addCylinder(trunk, base, 0.12f, height);
  Mesh leaves = makeMesh(kLeafAlbedo);
  addSphere(leaves, base + glm::vec3(0.0f, height, 0.0f), crown);
  addSphere(leaves, base + glm::vec3(0.6f * crown, height - 0.3f * crown, 0.2f), 0.7f * crown);
  addSphere(leaves, base + glm::vec3(-0.5f * crown, height - 0.2f * crown, -0.3f), 0.6f * crown);
  s.meshes.push_back(std::move(trunk));
  s.meshes.push_back(std::move(leaves));
}

// ESM Fig. 1/8, CSM Fig. 9: a fence of thin slats with objects and a tree behind it.
Scene backyard() {
  Scene s = sceneWithGround(
      "backyard", "fence of thin slats, objects and a tree: depth complexity that makes VSM bleed",
      glm::vec3(0.0f), 12.0f);
  Mesh fence = makeMesh(kWoodAlbedo);
  for (int i = -20; i <= 20; ++i)
    addBox(fence, glm::vec3(0.25f * float(i), 0.75f, 0.0f), glm::vec3(0.05f, 0.75f, 0.02f));
  addBox(fence, glm::vec3(0.0f, 1.25f, 0.05f), glm::vec3(5.2f, 0.06f, 0.03f));
  addBox(fence, glm::vec3(0.0f, 0.35f, 0.05f), glm::vec3(5.2f, 0.06f, 0.03f));
  s.meshes.push_back(std::move(fence));
  Mesh objects = makeMesh(kStoneAlbedo);
  addBox(objects, glm::vec3(-2.0f, 0.4f, 2.0f), glm::vec3(0.4f), 0.4f);
  addSphere(objects, glm::vec3(1.5f, 0.5f, 2.5f), 0.5f);
  addBox(objects, glm::vec3(3.0f, 0.25f, 1.2f), glm::vec3(0.6f, 0.25f, 0.3f), -0.3f);
  s.meshes.push_back(std::move(objects));
  addTree(s, glm::vec3(-3.5f, 0.0f, -2.5f), 3.0f, 1.2f);
  addTree(s, glm::vec3(2.5f, 0.0f, -3.0f), 3.5f, 1.4f);
  s.camera = {glm::vec3(0.5f, 5.0f, 11.0f), glm::vec3(0.0f, 1.0f, 0.5f), 45.0f};
  s.light = directional(glm::vec3(0.35f, -1.0f, 0.9f));
  s.troubleSpots = {{"fence shadow", {0.2f, 0.5f, 0.5f, 0.72f}},
                    {"box contact", {0.3f, 0.52f, 0.5f, 0.75f}},
                    {"sphere contact", {0.53f, 0.55f, 0.7f, 0.8f}}};
  return s;
}

// Thesis Fig. 3.4/3.5: canopy (A) over a bench (B) over the ground (C), a large A-B to B-C ratio.
Scene bench() {
  Scene s = sceneWithGround(
      "bench", "canopy above a bench above the ground: the three-object light-bleeding case",
      glm::vec3(0.0f), 6.0f);
  Mesh seat = makeMesh(kWoodAlbedo);
  addBox(seat, glm::vec3(0.0f, 0.45f, 0.0f), glm::vec3(1.5f, 0.04f, 0.35f));
  for (float x : {-1.3f, 1.3f}) {
    for (float z : {-0.28f, 0.28f})
      addBox(seat, glm::vec3(x, 0.22f, z), glm::vec3(0.04f, 0.22f, 0.04f));
  }
  s.meshes.push_back(std::move(seat));
  Mesh canopy = makeMesh(kLeafAlbedo);
  // Slatted canopy high above: its penumbrae fall across the bench and bleed onto the ground.
  for (int i = -6; i <= 6; ++i)
    addBox(canopy, glm::vec3(0.35f * float(i), 4.5f, 0.0f), glm::vec3(0.08f, 0.05f, 2.5f));
  s.meshes.push_back(std::move(canopy));
  s.camera = {glm::vec3(0.0f, 2.8f, 4.5f), glm::vec3(0.0f, 0.3f, 0.0f), 45.0f};
  s.light = directional(glm::vec3(0.08f, -1.0f, 0.05f));
  s.troubleSpots = {{"ground under the bench", {0.3f, 0.5f, 0.7f, 0.8f}}};
  return s;
}

// CSM Fig. 6, Gumbau Fig. 3: a slanted plane and boxes touching the ground.
Scene contact() {
  Scene s =
      sceneWithGround("contact", "a slanted plane and boxes touching the ground: contact shadows",
                      glm::vec3(0.0f), 5.0f);
  Mesh objects = makeMesh(kStoneAlbedo);
  const float tilt = 0.35f;
  const glm::mat3 axes(glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, std::cos(tilt), std::sin(tilt)),
                       glm::vec3(0.0f, -std::sin(tilt), std::cos(tilt)));
  scene::addOrientedBox(objects, glm::vec3(-1.0f, 0.02f + 1.2f * std::sin(tilt), 0.0f),
                        glm::vec3(0.8f, 0.02f, 1.2f), axes);
  addBox(objects, glm::vec3(1.2f, 0.3f, 0.3f), glm::vec3(0.3f), 0.5f);
  addBox(objects, glm::vec3(1.6f, 0.15f, -0.8f), glm::vec3(0.5f, 0.15f, 0.2f), -0.2f);
  s.meshes.push_back(std::move(objects));
  s.camera = {glm::vec3(0.0f, 2.5f, 4.0f), glm::vec3(0.2f, 0.2f, 0.0f), 45.0f};
  s.light = directional(glm::vec3(-0.6f, -1.0f, -0.4f));
  s.troubleSpots = {{"box contact", {0.52f, 0.4f, 0.78f, 0.7f}},
                    {"slanted plane contact", {0.1f, 0.6f, 0.45f, 0.8f}}};
  return s;
}

// Gumbau Fig. 3: stacked and overlapping spheres.
Scene spheres() {
  Scene s = sceneWithGround("spheres", "stacked and overlapping spheres", glm::vec3(0.0f), 5.0f);
  Mesh balls = makeMesh(glm::vec3(0.8f, 0.5f, 0.45f));
  addSphere(balls, glm::vec3(0.0f, 0.5f, 0.0f), 0.5f, 32);
  addSphere(balls, glm::vec3(0.2f, 1.25f, 0.1f), 0.35f, 32);
  addSphere(balls, glm::vec3(0.35f, 1.8f, 0.2f), 0.22f, 32);
  addSphere(balls, glm::vec3(-0.9f, 0.35f, 0.6f), 0.35f, 32);
  addSphere(balls, glm::vec3(-0.6f, 0.3f, 0.9f), 0.3f, 32);
  addSphere(balls, glm::vec3(1.1f, 0.25f, -0.5f), 0.25f, 32);
  s.meshes.push_back(std::move(balls));
  s.camera = {glm::vec3(0.5f, 2.5f, 4.0f), glm::vec3(0.0f, 0.5f, 0.0f), 45.0f};
  s.light =
      Light{LightKind::Spot, glm::vec3(0.0f), glm::vec3(2.5f, 5.0f, 1.5f), glm::vec3(0.0f), 70.0f};
  s.troubleSpots = {{"sphere contacts", {0.15f, 0.5f, 0.5f, 0.85f}}};
  return s;
}

// Thesis Fig. 4.3/4.8: many overlapping shadows at very different depths.
Scene overlap() {
  Scene s = sceneWithGround("overlap", "many overlapping shadows at different depths",
                            glm::vec3(0.0f), 6.0f);
  Mesh blades = makeMesh(kStoneAlbedo);
  for (int i = 0; i < 8; ++i) {
    const float height = 0.6f + 0.55f * float(i);
    addBox(blades, glm::vec3(0.25f * float(i) - 0.9f, height, 0.0f), glm::vec3(1.4f, 0.02f, 0.08f),
           0.4f * float(i));
  }
  addCylinder(blades, glm::vec3(-0.9f, 0.0f, 0.0f), 0.06f, 4.6f);
  s.meshes.push_back(std::move(blades));
  s.camera = {glm::vec3(0.0f, 3.0f, 5.0f), glm::vec3(0.0f, 0.3f, 0.0f), 45.0f};
  s.light = directional(glm::vec3(0.2f, -1.0f, 0.3f));
  s.troubleSpots = {{"overlapping blade shadows", {0.4f, 0.5f, 0.75f, 0.9f}}};
  return s;
}

// CSM Fig. 10, thesis Fig. 2.2: fine receding geometry seen from far away.
Scene minification() {
  Scene s = sceneWithGround("minification",
                            "fine receding rows of posts seen from far: minification aliasing",
                            glm::vec3(0.0f, 0.0f, -20.0f), 30.0f);
  Mesh posts = makeMesh(kWoodAlbedo);
  for (int row = 0; row < 40; ++row) {
    for (int i = -12; i <= 12; ++i) {
      addBox(posts, glm::vec3(0.3f * float(i), 0.4f, -1.2f * float(row)),
             glm::vec3(0.03f, 0.4f, 0.03f));
    }
  }
  s.meshes.push_back(std::move(posts));
  s.camera = {glm::vec3(0.0f, 2.0f, 6.0f), glm::vec3(0.0f, 0.0f, -20.0f), 40.0f};
  s.light = directional(glm::vec3(0.5f, -0.6f, -0.3f));
  s.pathOffset = glm::vec3(0.0f, 0.0f, -0.05f);  // creeping forward: minification flicker
  s.troubleSpots = {{"minified far posts", {0.35f, 0.38f, 0.65f, 0.52f}}};
  return s;
}

// Thesis §3.2: one planar occluder parallel to a planar receiver, both facing the light.
Scene planar() {
  Scene s = sceneWithGround(
      "planar", "a planar occluder parallel to a planar receiver: VSM is exact (thesis §3.2)",
      glm::vec3(0.0f), 4.0f);
  Mesh occluder = makeMesh(kStoneAlbedo);
  addGround(occluder, glm::vec3(0.0f, 1.5f, 0.0f), 1.0f);
  s.meshes.push_back(std::move(occluder));
  s.camera = {glm::vec3(0.0f, 5.0f, 5.0f), glm::vec3(0.0f, 0.0f, 0.0f), 45.0f};
  s.light = directional(glm::vec3(0.0f, -1.0f, 0.0f));
  s.troubleSpots = {{"penumbra edge", {0.35f, 0.45f, 0.65f, 0.75f}}};
  return s;
}

// Soft shadows' case (issue 11, PCSS: Fernando 2005): square plates floating at four heights
// and posts of three heights on the ground, so an area light's penumbrae widen with each
// blocker's distance to the ground (w = size (z_r - z_b) / z_b, soft_shadow.h) and narrow to the
// posts' feet (contact hardening).
Scene penumbrae() {
  Scene s = sceneWithGround("penumbrae",
                            "plates at four heights and posts of three heights: an area light's "
                            "penumbrae widen with the blocker-receiver distance",
                            glm::vec3(0.0f), 4.5f);
  Mesh plates = makeMesh(kStoneAlbedo);
  const float heights[4] = {0.2f, 0.6f, 1.2f, 2.2f};
  for (int i = 0; i < 4; ++i) {
    addBox(plates, glm::vec3(-3.3f + 2.0f * float(i), heights[i], -1.6f),
           glm::vec3(0.55f, 0.03f, 0.55f));
  }
  Mesh posts = makeMesh(kWoodAlbedo);
  const float postHeights[3] = {0.4f, 1.2f, 2.4f};
  for (int i = 0; i < 3; ++i) {
    addBox(posts, glm::vec3(-2.6f + 2.0f * float(i), 0.5f * postHeights[i], 0.9f),
           glm::vec3(0.1f, 0.5f * postHeights[i], 0.1f));
  }
  s.meshes.push_back(std::move(plates));
  s.meshes.push_back(std::move(posts));
  s.camera = {glm::vec3(0.0f, 5.5f, 5.5f), glm::vec3(0.0f, 0.0f, 0.3f), 50.0f};
  s.light = directional(glm::vec3(0.45f, -1.0f, 0.5f));
  s.troubleSpots = {{"high plate penumbra", {0.6f, 0.2f, 0.95f, 0.55f}},
                    {"low plate contact", {0.05f, 0.25f, 0.4f, 0.55f}},
                    {"post shadows", {0.2f, 0.55f, 0.8f, 0.85f}}};
  return s;
}

// Cascaded shadow maps' case: objects receding to the horizon along a street, seen at eye
// height. One map over the whole scene gives the near objects a few texels each.
Scene street() {
  Scene s = sceneWithGround("street",
                            "a street of posts, boxes and spheres receding to the horizon: one "
                            "shadow map is not enough (cascades)",
                            glm::vec3(0.0f, 0.0f, -110.0f), 120.0f);
  Mesh posts = makeMesh(kWoodAlbedo);
  Mesh blocks = makeMesh(kStoneAlbedo);
  for (int row = 0; row < 45; ++row) {
    const float z = 2.0f - 5.0f * float(row);
    for (float side : {-1.0f, 1.0f}) {
      addCylinder(posts, glm::vec3(side * 3.5f, 0.0f, z), 0.08f, 2.5f, 10);
      addBox(blocks, glm::vec3(side * 7.0f, 1.5f, z - 2.5f), glm::vec3(1.2f, 1.5f, 1.5f),
             0.2f * side);
    }
    if (row % 3 == 0)
      addSphere(blocks, glm::vec3(0.8f * float((row / 3) % 3 - 1), 0.5f, z), 0.5f, 16);
  }
  // A fence rail along the left: thin shadows that need resolution near the camera.
  for (int i = 0; i < 60; ++i) {
    addBox(posts, glm::vec3(-4.5f, 0.6f, 4.0f - 1.0f * float(i)), glm::vec3(0.03f, 0.6f, 0.03f));
  }
  s.meshes.push_back(std::move(posts));
  s.meshes.push_back(std::move(blocks));
  s.camera = {glm::vec3(0.0f, 1.7f, 8.0f), glm::vec3(0.0f, 1.2f, -30.0f), 50.0f};
  s.light = directional(glm::vec3(0.55f, -0.6f, -0.35f));
  s.pathOffset = glm::vec3(0.0f, 0.0f, -0.06f);  // walking down the street: cascade shimmer
  s.troubleSpots = {{"fence shadow near the camera", {0.0f, 0.6f, 0.4f, 1.0f}},
                    {"far shadows", {0.4f, 0.45f, 0.6f, 0.55f}}};
  return s;
}

// Point lights' case: a light at the centre of a box room, caged by 26 small cubes on the
// directions of a cube's face centres, edge midpoints and corners. Its shadow map's six faces meet
// along the cube's edges, so the shadows of the 18 edge and corner cubes straddle face edges and
// corners: a seam shows there (tests/gl/point_light_test.cpp measures it).
Scene lantern() {
  Scene s;
  s.name = "lantern";
  s.description =
      "a point light inside a room, caged by 26 cubes: shadows in all six directions, across "
      "every face edge and corner of the light's cube of shadow maps";
  // A closed box room, turned so the faces' edges cross its walls instead of running along its
  // edges. Flat walls: a tessellated sphere around the light would show its facets' ridges to
  // the filtered reference (each facet's receiver plane runs behind its neighbours).
  Mesh room = makeMesh(kGroundAlbedo);
  const glm::mat3 turn = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0.0f, 1.0f, 0.0f)) *
                                   glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(1.0f, 0.0f, 0.0f)));
  scene::addOrientedBox(room, glm::vec3(0.0f), glm::vec3(3.2f), turn);
  Mesh cage = makeMesh(kWoodAlbedo);
  for (int x = -1; x <= 1; ++x) {
    for (int y = -1; y <= 1; ++y) {
      for (int z = -1; z <= 1; ++z) {
        if (x == 0 && y == 0 && z == 0) continue;
        const glm::vec3 direction = glm::normalize(glm::vec3(float(x), float(y), float(z)));
        addBox(cage, 1.4f * direction, glm::vec3(0.17f), 0.35f * float(x + 2 * y + 3 * z));
      }
    }
  }
  s.meshes.push_back(std::move(room));
  s.meshes.push_back(std::move(cage));
  s.camera = {glm::vec3(-1.7f, -0.8f, 1.8f), glm::vec3(1.0f, 0.8f, -1.0f), 75.0f};
  s.light.kind = LightKind::Point;
  s.light.position = glm::vec3(0.0f);
  s.pathOffset = glm::vec3(0.02f, 0.0f, 0.0f);
  s.troubleSpots = {{"edge and corner shadows", {0.3f, 0.1f, 0.8f, 0.6f}}};
  return s;
}

struct SceneEntry {
  std::string_view name;
  Scene (*make)();
};

constexpr std::array<SceneEntry, 11> kScenes{{{"backyard", backyard},
                                              {"bench", bench},
                                              {"contact", contact},
                                              {"spheres", spheres},
                                              {"overlap", overlap},
                                              {"minification", minification},
                                              {"planar", planar},
                                              {"street", street},
                                              {"foliage", scene::makeFoliageScene},
                                              {"penumbrae", penumbrae},
                                              {"lantern", lantern}}};

constexpr std::array<std::string_view, 11> kSceneNames{
    "backyard", "bench",  "contact", "spheres",   "overlap", "minification",
    "planar",   "street", "foliage", "penumbrae", "lantern"};

}  // namespace

std::span<const std::string_view> builtinSceneNames() {
  return kSceneNames;
}

std::string builtinSceneNameList() {
  std::string list;
  for (std::string_view n : kSceneNames) list += (list.empty() ? "" : ", ") + std::string(n);
  return list;
}

Scene makeBuiltinScene(std::string_view name) {
  for (const SceneEntry& e : kScenes) {
    if (e.name == name) return e.make();
  }
  throw Error("unknown scene '" + std::string(name) + "'; valid scenes: " + builtinSceneNameList());
}

}  // namespace penumbra
