// A point light's faces (shared/point_light_faces.h, penumbra/point_light.h): every direction
// maps into its face's guarded region, neighbouring faces agree where their guard bands overlap,
// and the light pass's matrices project exactly as the lookup does.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "penumbra/error.h"
#include "penumbra/point_light.h"
#include "penumbra/shared/point_light_faces.h"

namespace penumbra {
namespace {

using shaders::pointFaceTangent;
using shaders::pointFaceUv;
using shaders::pointLightFace;

constexpr int kSize = 256;
constexpr int kGuard = 6;

std::vector<glm::vec3> randomDirections(int count) {
  std::mt19937 rng(7);
  std::normal_distribution<float> normal;
  std::vector<glm::vec3> out;
  while (int(out.size()) < count) {
    const glm::vec3 d(normal(rng), normal(rng), normal(rng));
    if (glm::length(d) > 1e-3f) out.push_back(glm::normalize(d));
  }
  return out;
}

TEST(PointLightFaces, EveryDirectionLandsInsideItsFacesNinetyDegreeRegion) {
  const float t = pointFaceTangent(kSize, kGuard);
  const float inner = float(kGuard) / float(kSize);  // the 90-degree face is [inner, 1 - inner]
  // Random directions, and the edges and corners themselves (ties go to the first axis).
  std::vector<glm::vec3> directions = randomDirections(20000);
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) directions.push_back(glm::vec3(float(x), float(y), float(z)));
  for (const glm::vec3& d : directions) {
    const int face = pointLightFace(d);
    ASSERT_GE(face, 0);
    ASSERT_LT(face, kPointLightFaceCount);
    const glm::vec3 uv = pointFaceUv(face, d, t);
    EXPECT_GT(uv.z, 0.0f) << "in front of its face";
    // float rounding of the division: 1e-6.
    EXPECT_GE(uv.x, inner - 1e-6f) << d.x << "," << d.y << "," << d.z;
    EXPECT_LE(uv.x, 1.0f - inner + 1e-6f) << d.x << "," << d.y << "," << d.z;
    EXPECT_GE(uv.y, inner - 1e-6f) << d.x << "," << d.y << "," << d.z;
    EXPECT_LE(uv.y, 1.0f - inner + 1e-6f) << d.x << "," << d.y << "," << d.z;
  }
}

TEST(PointLightFaces, DirectionInvertsTheFaceProjection) {
  // The area-light reference finds each pixel's receiver from its face, uv and distance.
  const float t = pointFaceTangent(kSize, kGuard);
  for (const glm::vec3& d : randomDirections(2000)) {
    const int face = pointLightFace(d);
    const glm::vec3 uv = pointFaceUv(face, d, t);
    const glm::vec3 back = shaders::pointFaceDirection(face, glm::vec2(uv.x, uv.y), t);
    EXPECT_NEAR(glm::dot(back, glm::normalize(d)), 1.0f, 1e-5f);  // fp32 round trip
  }
}

TEST(PointLightFaces, NeighbouringFacesAgreeWithinTheGuardBand) {
  // A direction within the guard band of a neighbouring face lands inside that face's map, at the
  // point the neighbour's own projection gives: the band holds the neighbour's texels.
  const float t = pointFaceTangent(kSize, kGuard);
  int overlaps = 0;
  for (const glm::vec3& d : randomDirections(20000)) {
    const int own = pointLightFace(d);
    for (int face = 0; face < kPointLightFaceCount; ++face) {
      if (face == own) continue;
      const glm::vec3 uv = pointFaceUv(face, d, t);
      if (uv.z <= 0.0f || uv.x < 0.0f || uv.x > 1.0f || uv.y < 0.0f || uv.y > 1.0f) continue;
      ++overlaps;
      // Within the band only: at most guard texels beyond the 90-degree face.
      const float beyond = std::max(
          {float(kGuard) / float(kSize) - uv.x, uv.x - (1.0f - float(kGuard) / float(kSize)),
           float(kGuard) / float(kSize) - uv.y, uv.y - (1.0f - float(kGuard) / float(kSize))});
      EXPECT_GT(beyond, -1e-6f) << "only the band overlaps";
      // Both faces see the same direction: unprojecting either uv gives d back.
      const shaders::PointFaceFrame f = shaders::pointLightFaceFrame(face);
      const glm::vec3 back = glm::normalize(f.forward + (2.0f * uv.x - 1.0f) * t * f.right +
                                            (2.0f * uv.y - 1.0f) * t * f.up);
      EXPECT_NEAR(glm::dot(back, d), 1.0f, 1e-5f);  // fp32 unprojection
    }
  }
  EXPECT_GT(overlaps, 100) << "the band must overlap its neighbours";
}

TEST(PointLightFaces, LightPassMatricesProjectLikeTheLookup) {
  Light light;
  light.kind = LightKind::Point;
  light.position = glm::vec3(0.5f, 1.0f, -2.0f);
  const Bounds bounds{glm::vec3(-5.0f), glm::vec3(5.0f)};
  const LightView view = fitLightView(light, bounds);
  EXPECT_TRUE(view.perspective);
  EXPECT_GT(view.farDistance, glm::length(light.position) + bounds.radius() - 1e-4f);
  const PointLightFaces faces = pointLightFaces(view, light.position, kSize, kGuard);
  EXPECT_FLOAT_EQ(faces.tangent, pointFaceTangent(kSize, kGuard));
  for (const glm::vec3& d : randomDirections(2000)) {
    const glm::vec3 world = light.position + 3.0f * d;
    const int face = pointLightFace(d);
    const glm::vec4 clip =
        faces.clipFromLight * faces.lightFromWorld[size_t(face)] * glm::vec4(world, 1.0f);
    const glm::vec2 ndc(clip.x / clip.w, clip.y / clip.w);
    const glm::vec3 uv = pointFaceUv(face, world - light.position, faces.tangent);
    // fp32 matrix products against a dot product: a few ulps of uv.
    EXPECT_NEAR(ndc.x * 0.5f + 0.5f, uv.x, 1e-5f);
    EXPECT_NEAR(ndc.y * 0.5f + 0.5f, uv.y, 1e-5f);
    EXPECT_GT(clip.w, 0.0f);
  }
}

TEST(PointLightFaces, UvStepIsTheProjectionsDerivative) {
  // Small steps: the derivative matches the difference of projections to first order. A step
  // of relative size s (here about 2e-3 of the distance) leaves a second-order remainder of
  // O(s) relative, up to a few times s at a guarded face's edge where the projection bends
  // most: 1e-2 relative, plus 1e-6 for fp32 cancellation in the difference. Large steps stay
  // finite where a difference of projections would cross behind the face.
  const float t = pointFaceTangent(kSize, kGuard);
  std::mt19937 rng(3);
  std::normal_distribution<float> normal;
  for (const glm::vec3& d : randomDirections(500)) {
    const glm::vec3 p = 2.0f * d;
    const int face = pointLightFace(p);
    const glm::vec3 delta = 2e-3f * glm::vec3(normal(rng), normal(rng), normal(rng));
    const glm::vec2 step = shaders::pointFaceUvStep(face, p, delta, t);
    const glm::vec3 a = pointFaceUv(face, p, t), b = pointFaceUv(face, p + delta, t);
    const glm::vec2 difference(b.x - a.x, b.y - a.y);
    EXPECT_NEAR(step.x, difference.x, 1e-2f * glm::length(difference) + 1e-6f);
    EXPECT_NEAR(step.y, difference.y, 1e-2f * glm::length(difference) + 1e-6f);
    const glm::vec2 far = shaders::pointFaceUvStep(face, p, -10.0f * p, t);
    EXPECT_TRUE(std::isfinite(far.x) && std::isfinite(far.y));
  }
}

TEST(PointLightFaces, AGuardBandWiderThanTheMapAllowsIsRefused) {
  const LightView view = fitLightView(Light{LightKind::Point}, Bounds{glm::vec3(-1), glm::vec3(1)});
  EXPECT_THROW(pointLightFaces(view, glm::vec3(0.0f), 64, 16), Error);
  EXPECT_NO_THROW(pointLightFaces(view, glm::vec3(0.0f), 64, 15));
}

TEST(LightKinds, UnknownNamesListTheValidOnes) {
  EXPECT_EQ(parseLightKind("point"), LightKind::Point);
  EXPECT_EQ(lightKindName(LightKind::Spot), "spot");
  try {
    parseLightKind("omni");
    FAIL() << "an unknown kind must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("directional, spot, point"), std::string::npos)
        << e.what();
  }
}

TEST(LightKinds, APointLightFromOverridesKeepsThePositionAndRefusesATarget) {
  Scene scene = makeBuiltinScene("planar");
  SceneOverrides o;
  o.lightKind = LightKind::Point;
  o.lightPosition = glm::vec3(0.0f, 2.0f, 0.0f);
  applyOverrides(scene, o);
  EXPECT_EQ(scene.light.kind, LightKind::Point);
  EXPECT_EQ(scene.light.position, glm::vec3(0.0f, 2.0f, 0.0f));
  o.lightTarget = glm::vec3(0.0f);
  EXPECT_THROW(applyOverrides(scene, o), Error);
  SceneOverrides size;
  size.lightSize = 11.0f;
  EXPECT_THROW(applyOverrides(scene, size), Error);  // [0, 10] for a point light
}

}  // namespace
}  // namespace penumbra
