// The ray-traced truth against closed forms: a square's hard shadow (edge exact to the
// sub-pixel), a disk and a sphere light over a straight edge, an alpha-masked checker card, and a
// plane under a grazing light that must not shadow itself. The expected values come from the
// geometry, computed here by unprojecting pixel centres independently of the tracer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "../common/edge_scenes.h"
#include "penumbra/error.h"
#include "penumbra/truth/true_shadow.h"

namespace penumbra::truth {
namespace {

// Where sub-pixel (bx, by) of a frame of bigWidth x bigHeight sub-pixels meets the plane y =
// height: the camera's near and far points of that sub-pixel unprojected through the inverse of
// the rasteriser's matrices.
glm::dvec3 groundPoint(const Scene& scene, int width, int height, int supersample, int bx, int by,
                       double planeHeight = 0.0) {
  const glm::dmat4 worldFromClip = glm::inverse(
      glm::dmat4(clipFromView(scene.camera, float(width) / float(height), scene.viewBounds())) *
      glm::dmat4(viewFromWorld(scene.camera)));
  const double ndcX = (double(bx) + 0.5) / double(width * supersample) * 2.0 - 1.0;
  const double ndcY = 1.0 - (double(by) + 0.5) / double(height * supersample) * 2.0;
  const glm::dvec4 a = worldFromClip * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
  const glm::dvec4 b = worldFromClip * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
  const glm::dvec3 nearPoint = glm::dvec3(a) / a.w, farPoint = glm::dvec3(b) / b.w;
  const double t = (nearPoint.y - planeHeight) / (nearPoint.y - farPoint.y);
  return nearPoint + (farPoint - nearPoint) * t;
}

TrueShadowRequest requestFor(const Scene& scene, int width, int height, int supersample,
                             int lightSamples = 1) {
  TrueShadowRequest r;
  r.camera = scene.camera;
  r.light = scene.light;
  r.viewBounds = scene.viewBounds();
  r.width = width;
  r.height = height;
  r.supersample = supersample;
  r.lightSamples = lightSamples;
  return r;
}

// A quad facing +y over [x0, x1] x [z0, z1] at height y, split into n x n cells (shared edges:
// shadow rays leaving one triangle pass over its neighbours).
void addGrid(Mesh& mesh, double x0, double x1, double z0, double z1, float y, int n) {
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      addQuad(mesh, float(x0 + (x1 - x0) * i / n), float(x0 + (x1 - x0) * (i + 1) / n),
              float(z0 + (z1 - z0) * j / n), float(z0 + (z1 - z0) * (j + 1) / n), y);
    }
  }
}

TEST(TrueShadow, SquareOccludersHardShadowIsExactToTheSubPixel) {
  Scene scene;
  Mesh ground, square;
  addQuad(ground, -4.0f, 4.0f, -4.0f, 4.0f, 0.0f);
  constexpr double kHalf = 0.5, kHeight = 1.0;
  addQuad(square, -float(kHalf), float(kHalf), -float(kHalf), float(kHalf), float(kHeight));
  scene.meshes = {ground, square};
  scene.camera = {glm::vec3(0.3f, 3.0f, 3.2f), glm::vec3(0.2f, 0.0f, 0.0f), 50.0f};
  scene.light.kind = LightKind::Directional;
  scene.light.direction = glm::vec3(0.35f, -1.0f, 0.2f);
  const int width = 120, height = 90, S = 3;
  const TrueShadow t = traceTrueShadow(RayScene(scene), requestFor(scene, width, height, S));
  const glm::dvec3 toLight = -glm::normalize(glm::dvec3(scene.light.direction));
  int compared = 0, shadowed = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double expected = 0.0;
      bool decidable = true;
      for (int s = 0; s < S * S; ++s) {
        const glm::dvec3 g = groundPoint(scene, width, height, S, x * S + s % S, y * S + s / S);
        if (std::max(std::abs(g.x), std::abs(g.z)) >= 4.0) decidable = false;  // off the ground
        // The camera sees the ground here, not the square's top.
        const glm::dvec3 top =
            groundPoint(scene, width, height, S, x * S + s % S, y * S + s / S, kHeight);
        if (std::abs(top.x) <= kHalf + 1e-4 && std::abs(top.z) <= kHalf + 1e-4) decidable = false;
        // The square's shadow: the ray to the light meets the square's plane inside it.
        const glm::dvec3 q = g + toLight * (kHeight / toLight.y);
        const double inside = std::max(std::abs(q.x), std::abs(q.z)) - kHalf;
        if (std::abs(inside) < 1e-5) decidable = false;  // within rounding of the edge
        expected += inside < 0.0 ? 0.0 : 1.0;
      }
      if (!decidable) continue;
      ASSERT_EQ(t.visibility.at(x, y), float(expected / (S * S))) << "pixel " << x << "," << y;
      ++compared;
      if (expected < 1.0) ++shadowed;
    }
  }
  // The shadow and its edges fill part of the frame, the edges cut through pixels.
  EXPECT_GT(compared, width * height / 2);
  EXPECT_GT(shadowed, 200);  // 351 at this view: the shadow is in the frame
  EXPECT_EQ(t.cameraRays, uint64_t(width * height * S * S));
}

struct EdgeErrors {
  double rmse = 0.0;
  double maxAbsolute = 0.0;
  int pixels = 0;
};

// The traced visibility against `analytic` averaged over each pixel's S x S sub-pixels' ground
// points (what the traced pixel estimates), over pixels within halfBand of the edge (x = 0), as
// the area-light reference's test measures it.
EdgeErrors edgeErrors(Scene scene, int lightSamples, double halfBand,
                      const std::function<double(glm::vec3)>& analytic) {
  // Zoomed on the penumbra under the camera's target so that most pixels measure it: every pixel
  // costs S^2 x samples rays (26 M at 4096 samples).
  scene.camera.verticalFovDegrees = 12.0f;
  const int width = 40, height = 40, S = 4;
  const TrueShadow t =
      traceTrueShadow(RayScene(scene), requestFor(scene, width, height, S, lightSamples));
  EdgeErrors e;
  double sum = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 centre = groundPoint(scene, width, height, 1, x, y);
      if (std::abs(centre.x) > halfBand || std::abs(centre.z) > 1.2) continue;
      double expected = 0.0;
      for (int s = 0; s < S * S; ++s) {
        expected +=
            analytic(glm::vec3(groundPoint(scene, width, height, S, x * S + s % S, y * S + s / S)));
      }
      const double error = double(t.visibility.at(x, y)) - expected / (S * S);
      sum += error * error;
      e.maxAbsolute = std::max(e.maxAbsolute, std::abs(error));
      ++e.pixels;
    }
  }
  e.rmse = std::sqrt(sum / std::max(e.pixels, 1));
  return e;
}

TEST(TrueShadow, DiskLightPenumbraEqualsTheClosedFormAndConverges) {
  const Scene scene = edgeScene();
  const auto analytic = [](glm::vec3 g) { return analyticDiskEdgeVisibility(g.x); };
  const EdgeErrors coarse = edgeErrors(scene, 64, 0.2, analytic);
  const EdgeErrors fine = edgeErrors(scene, 4096, 0.2, analytic);
  std::printf(
      "true shadow vs analytic disk-edge penumbra: 64 samples RMSE %.5f max %.5f, 4096 "
      "samples RMSE %.5f max %.5f (%d pixels)\n",
      coarse.rmse, coarse.maxAbsolute, fine.rmse, fine.maxAbsolute, fine.pixels);
  ASSERT_GT(fine.pixels, 300);  // the penumbra fills most of the zoomed frame
  // The bound at N = 4096. A chord crosses at most about 2 side cells of the stratified
  // grid, each off by at most 1/N: max <= 2 / side (0.031 at 4096, 0.25 at 64).
  EXPECT_LT(fine.rmse, 1e-3);
  EXPECT_LT(fine.maxAbsolute, 2.0 / 64.0);
  EXPECT_LT(coarse.maxAbsolute, 2.0 / 8.0);
  EXPECT_LT(fine.rmse, 0.25 * coarse.rmse);  // converges (as N^-3/4: 23x from 64 to 4096)
}

TEST(TrueShadow, SphereLightPenumbraEqualsTheClosedFormAndConverges) {
  const Scene scene = sphereEdgeScene();
  // 2000 midpoint steps: the closed form within 1e-6, 16 x 1400 times per trace.
  const auto analytic = [](glm::vec3 g) { return analyticSphereEdgeVisibility(g, 2000); };
  const EdgeErrors coarse = edgeErrors(scene, 64, 0.35, analytic);
  const EdgeErrors fine = edgeErrors(scene, 4096, 0.35, analytic);
  std::printf(
      "true shadow vs analytic sphere-edge penumbra: 64 samples RMSE %.5f max %.5f, "
      "4096 samples RMSE %.5f max %.5f (%d pixels)\n",
      coarse.rmse, coarse.maxAbsolute, fine.rmse, fine.maxAbsolute, fine.pixels);
  ASSERT_GT(fine.pixels, 300);
  EXPECT_LT(fine.rmse, 1e-3);
  EXPECT_LT(fine.rmse, 0.25 * coarse.rmse);
}

TEST(TrueShadow, AlphaMaskedCheckerCardCastsItsPattern) {
  // An 8 x 8 checker of opaque and clear texels on a card at height 1 over [-1, 1]^2, the sun
  // straight above: the ground under the card is shadowed exactly where the texel is opaque. The
  // camera looks from under the card's height, through its clear texels where it crosses them.
  constexpr int kTexels = 8;
  Scene scene;
  TextureImage checker;
  checker.name = "checker";
  checker.width = checker.height = kTexels;
  for (int j = 0; j < kTexels; ++j) {
    for (int i = 0; i < kTexels; ++i) {
      const uint8_t alpha = (i + j) % 2 == 0 ? 255 : 0;
      checker.rgba.insert(checker.rgba.end(), {255, 255, 255, alpha});
    }
  }
  scene.textures = {checker};
  Mesh ground, card;
  addQuad(ground, -3.0f, 3.0f, -3.0f, 3.0f, 0.0f);
  addQuad(card, -1.0f, 1.0f, -1.0f, 1.0f, 1.0f);
  for (Vertex& v : card.vertices)
    v.texcoord = (glm::vec2(v.position.x, v.position.z) + 1.0f) * 0.5f;
  card.baseColorTexture = 0;
  card.alphaMode = AlphaMode::Mask;
  card.alphaCutoff = 0.5f;
  scene.meshes = {ground, card};
  scene.camera = {glm::vec3(0.0f, 0.7f, 2.6f), glm::vec3(0.0f, 0.0f, 0.0f), 50.0f};
  scene.light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  const int width = 128, height = 96;
  const TrueShadow t = traceTrueShadow(RayScene(scene), requestFor(scene, width, height, 1));
  int compared = 0;
  double shadowedShare = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 g = groundPoint(scene, width, height, 1, x, y);
      if (std::abs(g.x) >= 1.0 || std::abs(g.z) >= 1.0) continue;
      // Bilinear alpha crosses the cutoff on texel boundaries: keep clear of them.
      const glm::dvec2 texel = (glm::dvec2(g.x, g.z) + 1.0) * 0.5 * double(kTexels);
      const glm::dvec2 fromEdge = glm::abs(texel - glm::floor(texel) - 0.5);
      if (std::max(fromEdge.x, fromEdge.y) > 0.45) continue;
      const bool opaque = (int(texel.x) + int(texel.y)) % 2 == 0;
      ASSERT_EQ(t.visibility.at(x, y), opaque ? 0.0f : 1.0f) << "pixel " << x << "," << y;
      ++compared;
      shadowedShare += opaque ? 1.0 : 0.0;
    }
  }
  ASSERT_GT(compared, 1000);
  // The pattern's coverage: half the texels are opaque (the pixels sample them unevenly in
  // perspective, hence the 0.1).
  EXPECT_NEAR(shadowedShare / compared, 0.5, 0.1);
}

TEST(TrueShadow, TranslucentCardsLetThroughTheProductOfOneMinusAlpha) {
  // Two BLEND cards under the sun straight above: alpha 0.25 at height 1 over [-1, 1]^2, alpha
  // 0.5 at height 1.5 over x in [0, 1]. The ground under the first alone keeps 0.75 of the light,
  // under both 0.75 x 0.5 = 0.375 (each a few float products: exact). The camera looks from under
  // the cards (the camera sees BLEND as a mask at 0.5, so the upper card would hide the ground).
  Scene scene;
  Mesh ground, low, high;
  addQuad(ground, -3.0f, 3.0f, -3.0f, 3.0f, 0.0f);
  addGrid(low, -1.0, 1.0, -1.0, 1.0, 1.0f, 4);  // shared edges: each crossed once
  addQuad(high, 0.0f, 1.0f, -1.0f, 1.0f, 1.5f);
  low.alphaMode = high.alphaMode = AlphaMode::Blend;
  low.opacity = 0.25f;
  high.opacity = 0.5f;
  scene.meshes = {ground, low, high};
  scene.camera = {glm::vec3(0.0f, 0.7f, 2.6f), glm::vec3(0.0f, 0.0f, 0.0f), 50.0f};
  scene.light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  const int width = 128, height = 96;
  const TrueShadow t = traceTrueShadow(RayScene(scene), requestFor(scene, width, height, 1));
  int underOne = 0, underBoth = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 g = groundPoint(scene, width, height, 1, x, y);
      // Clear of the cards' edges and of the low card's inner edges (x, z in {-0.5, 0, 0.5}).
      const auto nearInnerEdge = [](double v) {
        return std::abs(v - std::round(v * 2.0) / 2.0) < 0.02;
      };
      if (std::abs(g.x) >= 0.98 || std::abs(g.z) >= 0.98 || nearInnerEdge(g.x) ||
          nearInnerEdge(g.z)) {
        continue;
      }
      const bool both = g.x > 0.0;
      ASSERT_EQ(t.visibility.at(x, y), both ? 0.375f : 0.75f) << "pixel " << x << "," << y;
      ++(both ? underBoth : underOne);
    }
  }
  EXPECT_GT(underOne, 500);
  EXPECT_GT(underBoth, 500);
}

TEST(TrueShadow, PlaneUnderAGrazingLightDoesNotShadowItself) {
  // A plane of 32 x 32 quads far from the origin (coordinates near 100, where a float's ulp is
  // 8e-6 and the barycentric hit point's rounding a few of them), tilted 20 degrees about an
  // oblique axis so that no coordinate is constant over it, lit at 85 degrees from its normal:
  // every shadow ray leaves at 5 degrees over triangles it must not hit.
  Scene scene;
  Mesh plane;
  addGrid(plane, -10.0, 10.0, -10.0, 10.0, 0.0f, 32);
  const glm::vec3 centre(100.0f, 3.7f, -40.0f);
  const glm::mat3 tilt(glm::rotate(glm::mat4(1.0f), glm::radians(20.0f),
                                   glm::normalize(glm::vec3(1.0f, 0.0f, 0.6f))));
  for (Vertex& v : plane.vertices) {
    v.position = centre + tilt * v.position;
    v.normal = tilt * v.normal;
  }
  scene.meshes = {plane};
  const glm::vec3 normal = tilt * glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 along = glm::normalize(tilt * glm::vec3(1.0f, 0.0f, 0.3f));
  const float grazing = glm::radians(85.0f);
  scene.light.direction = -(std::cos(grazing) * normal + std::sin(grazing) * along);
  scene.camera = {centre + 9.0f * normal + 12.0f * (tilt * glm::vec3(0.0f, 0.0f, 1.0f)), centre,
                  60.0f};
  const int width = 160, height = 120;
  const TrueShadow t = traceTrueShadow(RayScene(scene), requestFor(scene, width, height, 2));
  int covered = 0, selfShadowed = 0;
  for (float v : t.visibility.data()) {
    if (v < 0.0f) continue;
    ++covered;
    if (v != 1.0f) ++selfShadowed;
  }
  ASSERT_GT(covered, width * height / 2);
  EXPECT_EQ(selfShadowed, 0);
}

TEST(TrueShadow, LightSampleCountsAreChecked) {
  for (int ok : {1, 4, 64, 4096}) EXPECT_NO_THROW(checkTrueShadowLightSamples(ok));
  for (int bad : {0, -4, 2, 4097, 65 * 65}) {
    try {
      checkTrueShadowLightSamples(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("side in [1, 64]"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace penumbra::truth
