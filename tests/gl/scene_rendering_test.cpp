// Scenes from files and alpha-masked casters through the renderer: a striped alpha-masked quad's
// shadow is lit where the texture is transparent, for every technique and with MSAA; a node
// hierarchy renders as its flattened geometry; a real glTF model renders finite with every
// technique. Also the report's crops for scenes without trouble spots.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "../scene/scene_fixtures.h"
#include "gl_test_context.h"
#include "penumbra/compare/error_regions.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/scene_animation.h"
#include "penumbra/technique.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

class SceneRenderingTest : public testing::GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (context) renderer = std::make_unique<gl::Renderer>(*context);
  }
  std::unique_ptr<gl::Renderer> renderer;
};

void addQuad(Mesh& mesh, float y, glm::vec2 lo, glm::vec2 hi) {
  const uint32_t base = uint32_t(mesh.vertices.size());
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  mesh.vertices.push_back({{lo.x, y, lo.y}, up, {0.0f, 0.0f}});
  mesh.vertices.push_back({{lo.x, y, hi.y}, up, {0.0f, 1.0f}});
  mesh.vertices.push_back({{hi.x, y, hi.y}, up, {1.0f, 1.0f}});
  mesh.vertices.push_back({{hi.x, y, lo.y}, up, {1.0f, 0.0f}});
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
}

// A 1 m quad at height 1 over x, z in [-0.5, 0.5], textured with 16 columns of which every
// fourth (u in [k/4, k/4 + 1/16)) is opaque: a quarter covers. The light travels along
// (1, -1, 0), so the quad's shadow is the ground's x in [0.5, 1.5]; the camera looks straight
// down at it. Bilinear alpha crosses the 0.5 cutoff exactly on texel boundaries, so the shadow's
// stripes are the covered columns exactly.
Scene stripedQuadScene() {
  Scene s;
  s.name = "striped_quad";
  Mesh ground;
  ground.albedo = glm::vec3(0.8f);
  addQuad(ground, 0.0f, {-2.0f, -2.0f}, {2.0f, 2.0f});
  Mesh card;
  card.albedo = glm::vec3(1.0f);
  card.baseColorTexture = 0;
  card.alphaMode = AlphaMode::Mask;
  addQuad(card, 1.0f, {-0.5f, -0.5f}, {0.5f, 0.5f});
  s.meshes = {ground, card};
  TextureImage stripes;
  stripes.width = 16;
  stripes.height = 16;
  stripes.rgba.assign(16 * 16 * 4, 255);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) stripes.rgba[size_t(y * 16 + x) * 4 + 3] = x % 4 == 0 ? 255 : 0;
  }
  s.textures = {stripes};
  s.light.kind = LightKind::Directional;
  s.light.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  s.camera = {glm::vec3(1.0f, 4.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), 45.0f};
  return s;
}

// Mean of a one-channel image over the pixels whose point on the horizontal plane at `height`
// (the ground: 0) lies in x in [x0, x1], z in [z0, z1], and that rectangle's exact width in
// metres (whole pixels).
struct RegionMean {
  double mean;
  double widthMetres;
};

RegionMean groundRegionMean(const Image& visibility, const Scene& s, float x0, float x1, float z0,
                            float z1, float height = 0.0f) {
  const float aspect = float(visibility.width()) / float(visibility.height());
  const glm::mat4 clipFromWorld =
      clipFromView(s.camera, aspect, s.viewBounds()) * viewFromWorld(s.camera);
  double sum = 0.0;
  int count = 0, minColumn = INT32_MAX, maxColumn = -1;
  for (int y = 0; y < visibility.height(); ++y) {
    for (int x = 0; x < visibility.width(); ++x) {
      // The ground point at this pixel's centre: the ray from the camera through it, at y = 0.
      const glm::vec2 ndc((float(x) + 0.5f) / float(visibility.width()) * 2.0f - 1.0f,
                          1.0f - (float(y) + 0.5f) / float(visibility.height()) * 2.0f);
      const glm::mat4 worldFromClip = glm::inverse(clipFromWorld);
      glm::vec4 far = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
      const glm::vec3 farPoint = glm::vec3(far) / far.w;
      const glm::vec3 dir = farPoint - s.camera.position;
      const glm::vec3 ground = s.camera.position - dir * ((s.camera.position.y - height) / dir.y);
      if (ground.x >= x0 && ground.x <= x1 && ground.z >= z0 && ground.z <= z1) {
        sum += visibility.at(x, y);
        ++count;
        minColumn = std::min(minColumn, x);
        maxColumn = std::max(maxColumn, x);
      }
    }
  }
  // Pixels per metre on the plane: the image height spans 2 * (4 m - height) * tan(22.5 degrees).
  const double metresPerPixel =
      2.0 * (4.0 - height) * std::tan(glm::radians(22.5)) / visibility.height();
  return {count > 0 ? sum / count : -1.0, double(maxColumn - minColumn + 1) * metresPerPixel};
}

TEST_F(SceneRenderingTest, AlphaMaskedQuadShadowIsLitWhereTheTextureIsTransparent) {
  if (!renderer) GTEST_SKIP();
  const Scene s = stripedQuadScene();
  gl::RenderSettings settings;
  settings.technique = Technique::Hard;
  settings.shadowMapSize = 1024;
  settings.width = settings.height = 512;
  settings.blur.radius = 0;
  // Two stripe periods (0.5 m) from a lit phase to the same phase: the region holds exactly two
  // covered stripes of 1/16 m, whatever pixel its edges fall on.
  for (int msaa : {1, 4}) {
    settings.msaaSamples = msaa;
    const gl::RenderResult r = renderer->render(s, settings);
    const RegionMean m = groundRegionMean(r.visibility, s, 0.65f, 1.15f, -0.4f, 0.4f);
    const double expected = 1.0 - 2.0 * 0.0625 / m.widthMetres;
    // A stripe is 11 shadow-map texels wide (texel 5.7 mm: a 5.8 m sphere fit over 1024); each
    // of the four stripe edges may land half a texel off: 4 x 2.8 mm of 500 mm = 0.023.
    EXPECT_NEAR(m.mean, expected, 0.023) << "msaa " << msaa;
  }
}

// The camera pass cuts masked texels out as the light pass does (the alpha-tested variant,
// gl/material_programs.h): looking down through the striped card, a quarter of its pixels show
// the card and the rest the ground beneath. Both are lit there (the card's shadow falls at
// x > 0.5), so the card (albedo 1) shades brighter than the ground (albedo 0.8).
TEST_F(SceneRenderingTest, TheCameraSeesTheGroundThroughAnAlphaMaskedCard) {
  if (!renderer) GTEST_SKIP();
  const Scene s = stripedQuadScene();
  for (Technique t : {Technique::Hard, Technique::Vsm}) {
    gl::RenderSettings settings;
    settings.technique = t;
    settings.width = settings.height = 512;
    const gl::RenderResult r = renderer->render(s, settings);
    float brightest = 0.0f;
    for (int y = 0; y < r.color.height(); ++y) {
      for (int x = 0; x < r.color.width(); ++x)
        brightest = std::max(brightest, r.color.at(x, y, 0));
    }
    // 1 where the pixel shades as the card, between the ground's 0.8 and the card's 1 of it.
    Image card(r.color.width(), r.color.height(), 1);
    for (int y = 0; y < card.height(); ++y) {
      for (int x = 0; x < card.width(); ++x) card.at(x, y) = r.color.at(x, y, 0) > 0.9f * brightest;
    }
    // Two stripe periods of the card's plane (u = x + 0.5: opaque columns at x in [0, 1/16) and
    // [1/4, 5/16)): exactly two covered stripes of 1/16 m in 0.5 m.
    const RegionMean m = groundRegionMean(card, s, -0.1f, 0.4f, -0.4f, 0.4f, 1.0f);
    // The plane is 3 m from the camera: 206 pixels a metre, 103 across the region; each of the
    // four stripe edges may fall one pixel either way: 4 / 103 = 0.039.
    EXPECT_NEAR(m.mean, 0.25, 0.039) << techniqueId(t);
  }
}

TEST_F(SceneRenderingTest, AlphaMaskedQuadCastsAHoledShadowWithEveryTechnique) {
  if (!renderer) GTEST_SKIP();
  const Scene s = stripedQuadScene();
  for (Technique t : allTechniques()) {
    for (int msaa : {1, 4}) {
      gl::RenderSettings settings;
      settings.technique = t;
      settings.shadowMapSize = 512;
      settings.width = settings.height = 256;
      settings.msaaSamples = msaa;
      const gl::RenderResult r = renderer->render(s, settings);
      const RegionMean m = groundRegionMean(r.visibility, s, 0.65f, 1.15f, -0.4f, 0.4f);
      // The exact lit share is 0.75; the techniques' approximations move it (power-CDF darkens
      // most: 0.52 measured with 4x MSAA), but a card without holes would give 0 and no card 1.
      EXPECT_GT(m.mean, 0.4) << techniqueId(t) << " msaa " << msaa;
      EXPECT_LT(m.mean, 0.95) << techniqueId(t) << " msaa " << msaa;
    }
  }
}

const std::vector<glm::vec3> kQuad{
    {-0.5f, 0.0f, -0.5f}, {-0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, -0.5f}};

// The striped quad's scene with the card translucent instead: BLEND at alpha 0.25, no texture.
Scene translucentCardScene() {
  Scene s = stripedQuadScene();
  Mesh& card = s.meshes[1];
  card.baseColorTexture = -1;
  card.alphaMode = AlphaMode::Blend;
  card.opacity = 0.25f;
  s.textures.clear();
  return s;
}

// Visibility over the middle of the card's shadow (ground x in [0.5, 1.5], z in [-0.5, 0.5]),
// kept a kernel's width off its edges: its mean and the pixels' largest distance from `expected`.
struct ShadowMiddle {
  double mean = 0.0;
  double worst = 0.0;
};
ShadowMiddle translucentShadowMiddle(const Image& visibility, const Scene& s, double expected) {
  ShadowMiddle m;
  m.mean = groundRegionMean(visibility, s, 0.75f, 1.25f, -0.25f, 0.25f).mean;
  const float aspect = float(visibility.width()) / float(visibility.height());
  const glm::mat4 clipFromWorld =
      clipFromView(s.camera, aspect, s.viewBounds()) * viewFromWorld(s.camera);
  for (float x = 0.75f; x <= 1.25f; x += 0.01f) {
    for (float z = -0.25f; z <= 0.25f; z += 0.01f) {
      const glm::vec4 clip = clipFromWorld * glm::vec4(x, 0.0f, z, 1.0f);
      const int px = int((clip.x / clip.w * 0.5f + 0.5f) * float(visibility.width()));
      const int py = int((0.5f - clip.y / clip.w * 0.5f) * float(visibility.height()));
      m.worst = std::max(m.worst, std::abs(double(visibility.at(px, py)) - expected));
    }
  }
  return m;
}

// A BLEND card at alpha 0.25 darkens its shadow by a quarter: the light pass covers a dithered
// quarter of the texels under it and the 5-tap box with bilinear lookups averages them, in the
// filtered reference and the techniques that carry translucency (carriesTranslucency). The
// mean over the shadow's middle within 0.025 of 0.75 (measured: 0.746-0.771, ESM's
// alpha exp(-c depth gap) term the largest); each pixel within 0.15 (a 5x5 window over the 4x4
// dither holds 4 to 9 of its covered texels, 0.64-0.84 before bilinear blending; measured
// 0.11-0.12). The others (the hard test, EVSM2, the power-function CDF) draw the card as a mask
// at 0.5, which alpha 0.25 does not reach: no shadow at all under it.
TEST_F(SceneRenderingTest, ATranslucentCardLetsThroughOneMinusAlpha) {
  if (!renderer) GTEST_SKIP();
  const Scene s = translucentCardScene();
  gl::RenderSettings settings;
  settings.shadowMapSize = 512;
  settings.width = 320;
  settings.height = 180;
  settings.blur = BlurSpec{BlurKernel::Box, 2, 1.0f};
  settings.filter = FilterMode::Bilinear;
  settings.technique = Technique::Pcf;
  constexpr double kMeanTolerance = 0.025, kPixelTolerance = 0.15;
  const ShadowMiddle reference =
      translucentShadowMiddle(renderer->renderReference(s, settings, 1).visibility, s, 0.75);
  EXPECT_NEAR(reference.mean, 0.75, kMeanTolerance) << "filtered reference";
  EXPECT_LE(reference.worst, kPixelTolerance) << "filtered reference";
  for (Technique t : allTechniques()) {
    settings.technique = t;
    const ShadowMiddle m =
        translucentShadowMiddle(renderer->render(s, settings).visibility, s, 0.75);
    if (carriesTranslucency(t)) {
      EXPECT_NEAR(m.mean, 0.75, kMeanTolerance) << techniqueId(t);
      EXPECT_LE(m.worst, kPixelTolerance) << techniqueId(t);
    } else {
      EXPECT_EQ(m.mean, 1.0) << techniqueId(t);  // the mask: nothing under a card at 0.25
    }
  }
  // The front ends name the ones that cannot.
  const std::string warning = translucencyWarning(s, allTechniques());
  EXPECT_NE(warning.find("but hard, evsm2, powercdf cannot carry it and draw them as a mask"),
            std::string::npos)
      << warning;
  EXPECT_EQ(translucencyWarning(stripedQuadScene(), allTechniques()), "");  // a mask, not BLEND
}

TEST_F(SceneRenderingTest, NodeHierarchyRendersAsItsFlattenedGeometry) {
  if (!renderer) GTEST_SKIP();
  // Hierarchy: the ground (node 0: the quad scaled by 8) and a caster under a parent with
  // translation, rotation and scale (nodes 1, 2).
  const std::string nodes =
      R"([{"scale":[4,1,4],"mesh":0},)"
      R"({"translation":[0,1,0],"rotation":[0,0.258819045,0,0.965925826],"scale":[1.5,1.5,1.5],)"
      R"("children":[2]},{"translation":[0.5,0,0],"mesh":0}])";
  const fs::path dir = fs::path(::testing::TempDir());
  const fs::path hierarchy =
      testing::writeFile(dir / "hierarchy_render.gltf",
                         testing::gltfWithMesh(kQuad, {0, 1, 2, 0, 2, 3}, nodes, "[0,1]"));
  // Flattened: the same quads in world space in one mesh, under one node without a transform.
  const glm::mat4 caster = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0)) *
                           glm::scale(glm::mat4(1.0f), glm::vec3(1.5f)) *
                           glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0, 0));
  std::vector<glm::vec3> flat;
  for (glm::vec3 p : kQuad) flat.push_back(p * glm::vec3(4.0f, 1.0f, 4.0f));
  for (glm::vec3 p : kQuad) flat.push_back(glm::vec3(caster * glm::vec4(p, 1.0f)));
  const fs::path flattened = testing::writeFile(
      dir / "flattened_render.gltf",
      testing::gltfWithMesh(flat, {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}, R"([{"mesh":0}])", "[0]"));
  gl::RenderSettings settings;
  settings.technique = Technique::Pcf;
  settings.shadowMapSize = 512;
  settings.width = 320;
  settings.height = 180;
  const gl::RenderResult a = renderer->render(loadScene(hierarchy.string()), settings);
  const gl::RenderResult b = renderer->render(loadScene(flattened.string()), settings);
  size_t differing = 0, shadowed = 0;
  for (size_t i = 0; i < a.visibility.data().size(); ++i) {
    differing += std::abs(a.visibility.data()[i] - b.visibility.data()[i]) > 0.01f;
    shadowed += a.visibility.data()[i] < 0.5f;
  }
  EXPECT_GT(shadowed, 500u);  // the caster's shadow is in view
  // The file's quaternion has 9 digits and the two sides compose in different orders: positions
  // agree to ~1e-6 m, far below a texel (1.1 cm), so at most a handful of edge pixels differ.
  EXPECT_LE(differing, 5u);
}

// The waving-bars fixture (scripts/make-waving-bars) at the clip's start and at 1 s, its bars
// bent by 8 to 44 degrees: the shadows move, and the renderer's in-place update of the vertices
// for the new pose renders exactly what a fresh upload of that pose does.
TEST_F(SceneRenderingTest, AnAnimatedSceneShadowMovesAndANewPoseRendersAsAFreshUpload) {
  if (!renderer) GTEST_SKIP();
  Scene scene = loadScene(PENUMBRA_SOURCE_DIR "/tests/data/waving_bars.gltf");
  ASSERT_TRUE(scene.animation.moves());
  gl::RenderSettings settings;
  settings.technique = Technique::Pcf;
  settings.shadowMapSize = 512;
  settings.width = 320;
  settings.height = 180;
  const gl::RenderResult start = renderer->render(scene, settings);
  poseScene(scene, 1.0f);
  const gl::RenderResult bent = renderer->render(scene, settings);  // vertices updated in place
  gl::Renderer fresh(*context);
  const gl::RenderResult uploaded = fresh.render(scene, settings);
  size_t moved = 0, differing = 0;
  for (size_t i = 0; i < bent.visibility.data().size(); ++i) {
    moved += std::abs(bent.visibility.data()[i] - start.visibility.data()[i]) > 0.5f;
    differing += bent.visibility.data()[i] != uploaded.visibility.data()[i];
  }
  // The same vertices on the same GL: the same bits.
  EXPECT_EQ(differing, 0u);
  // The frame holds the 14 m ground at about 11 pixels a metre: each bar's shadow is about 3 by
  // 33 pixels, of which the part cast by its bending upper two thirds swings off itself; about
  // 30 pixels a bar, 750 in all, change between lit and shadowed (733 measured on llvmpipe).
  // Not updating the vertices moves none.
  EXPECT_GT(moved, 300u);
}

TEST_F(SceneRenderingTest, RealGltfModelRendersFiniteWithEveryTechnique) {
  if (!renderer) GTEST_SKIP();
  const Scene s =
      loadScene("/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  for (Technique t : allTechniques()) {
    gl::RenderSettings settings;
    settings.technique = t;
    settings.shadowMapSize = 512;
    settings.width = 160;
    settings.height = 90;
    const gl::RenderResult r = renderer->render(s, settings);
    float lo = 1.0f, hi = 0.0f;
    for (float v : r.visibility.data()) {
      ASSERT_TRUE(std::isfinite(v)) << techniqueId(t);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    for (float c : r.color.data()) ASSERT_TRUE(std::isfinite(c)) << techniqueId(t);
    EXPECT_LT(lo, 0.5f) << techniqueId(t);  // the engine shadows itself
    EXPECT_EQ(hi, 1.0f) << techniqueId(t);
    // 115 primitives of 32-byte vertices and 4-byte indices: a few MiB.
    EXPECT_GT(r.memory.geometry, 121496u * 3u * 4u) << techniqueId(t);
  }
}

TEST(ErrorRegions, FindTheBlobOfLargestErrorFirst) {
  Image error(100, 50, 1, 0.0f);
  for (int y = 30; y < 40; ++y) {
    for (int x = 70; x < 80; ++x) error.at(x, y) = 0.5f;
  }
  error.at(5, 5) = 0.1f;
  const std::vector<TroubleSpot> spots = compare::largestErrorRegions({error}, 3);
  ASSERT_EQ(spots.size(), 2u);  // windows without error are not offered
  EXPECT_EQ(spots[0].name, "largest error 1");
  // The first window (20 x 10 pixels) holds the whole 10 x 10 blob (1e-3: float rectangles).
  EXPECT_LE(spots[0].rect.x * 100.0f, 70.001f);
  EXPECT_GE(spots[0].rect.z * 100.0f, 79.999f);
  EXPECT_LE(spots[0].rect.y * 50.0f, 30.001f);
  EXPECT_GE(spots[0].rect.w * 50.0f, 39.999f);
  EXPECT_LE(spots[1].rect.x * 100.0f, 5.001f);
}

}  // namespace
}  // namespace penumbra
