// Cascade splits, per-pixel selection and blend weights, and the stabilised fit's invariance.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/cascades.h"
#include "penumbra/error.h"
#include "penumbra/shared/cascade_selection.h"

namespace penumbra {
namespace {

using shaders::CascadeChoice;
using shaders::selectCascade;

TEST(CascadeSplits, PracticalSchemeMixesLogarithmicAndUniformByLambda) {
  // PSSM eq. 9 by hand for near 1, far 16, 4 splits: log ends 2, 4, 8, 16; uniform 4.75, 8.5,
  // 12.25, 16.
  const std::vector<float> log = practicalSplitEnds(1.0f, 16.0f, 4, 1.0f);
  const std::vector<float> uni = practicalSplitEnds(1.0f, 16.0f, 4, 0.0f);
  const std::vector<float> half = practicalSplitEnds(1.0f, 16.0f, 4, 0.5f);
  const float logEnds[4] = {2.0f, 4.0f, 8.0f, 16.0f};
  const float uniEnds[4] = {4.75f, 8.5f, 12.25f, 16.0f};
  for (int i = 0; i < 4; ++i) {
    // pow's rounding: a few ulp at these magnitudes.
    EXPECT_NEAR(log[size_t(i)], logEnds[i], 1e-5f) << i;
    EXPECT_NEAR(uni[size_t(i)], uniEnds[i], 1e-5f) << i;
    EXPECT_NEAR(half[size_t(i)], 0.5f * (logEnds[i] + uniEnds[i]), 1e-5f) << i;
  }
}

TEST(CascadeSelection, PicksTheCascadeWhoseRangeHoldsTheDepth) {
  const glm::vec4 ends0(2.0f, 4.0f, 8.0f, 16.0f), ends1(0.0f);
  const float depths[] = {1.5f, 2.5f, 5.0f, 15.0f};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(selectCascade(depths[i], 1.0f, ends0, ends1, 4, 0.0f).index, i);
  }
  EXPECT_EQ(selectCascade(17.0f, 1.0f, ends0, ends1, 4, 0.0f).index, 4) << "beyond the last";
}

TEST(CascadeSelection, BlendRisesLinearlyAcrossTheBandAndNeverPastTheLastCascade) {
  const glm::vec4 ends0(2.0f, 4.0f, 8.0f, 16.0f), ends1(0.0f);
  // Cascade 1 spans [2, 4): with band 0.25 its last 0.5 fades into cascade 2.
  EXPECT_EQ(selectCascade(3.4f, 1.0f, ends0, ends1, 4, 0.25f).blend, 0.0f);
  const CascadeChoice mid = selectCascade(3.75f, 1.0f, ends0, ends1, 4, 0.25f);
  EXPECT_EQ(mid.index, 1);
  EXPECT_NEAR(mid.blend, 0.5f, 1e-6f);
  // The last cascade has nothing to fade into.
  EXPECT_EQ(selectCascade(15.9f, 1.0f, ends0, ends1, 4, 0.25f).blend, 0.0f);
  // Cascades 4..7 come from the second vector.
  const glm::vec4 more(20.0f, 24.0f, 28.0f, 32.0f);
  EXPECT_EQ(selectCascade(21.0f, 1.0f, ends0, more, 8, 0.0f).index, 5);
}

TEST(CascadeUv, MapsTheBoxOntoTheUnitSquare) {
  const glm::vec4 box(-2.0f, 1.0f, 4.0f, 8.0f);
  const glm::vec2 corner = shaders::cascadeUv(glm::vec2(-2.0f, 1.0f), box, 0);
  const glm::vec2 far = shaders::cascadeUv(glm::vec2(2.0f, 9.0f), box, 0);
  EXPECT_EQ(corner, glm::vec2(0.0f));
  EXPECT_EQ(far, glm::vec2(1.0f));
  EXPECT_EQ(shaders::cascadeUv(glm::vec2(4.0f, 4.0f), box, 1), glm::vec2(1.0f, 0.5f));
  // A depth slope of 1 per light-view unit is 4/256 per texel across a 4-unit, 256-texel map.
  EXPECT_EQ(shaders::cascadeDepthPerTexel(glm::vec2(1.0f), box, 256),
            glm::vec2(4.0f / 256.0f, 8.0f / 256.0f));
}

class CascadeFitTest : public ::testing::Test {
 protected:
  CascadeFrame fit(const Camera& from, CascadeFit how) const {
    CascadeSettings s;
    s.count = 4;
    s.fit = how;
    return fitCascades(s, from, 16.0f / 9.0f, {0.05f, 100.0f}, light, bounds, 1024);
  }
  Light light{LightKind::Directional, glm::normalize(glm::vec3(0.5f, -0.6f, -0.3f))};
  Bounds bounds{glm::vec3(-100.0f, 0.0f, -100.0f), glm::vec3(100.0f, 10.0f, 100.0f)};
  Camera camera{glm::vec3(0.3f, 1.7f, 8.0f), glm::vec3(0.3f, 1.2f, -30.0f), 50.0f};
};

TEST_F(CascadeFitTest, EveryCascadeBoxCoversItsSliceIncludingTheBlendBand) {
  for (CascadeFit how : {CascadeFit::Tight, CascadeFit::Stabilized}) {
    const CascadeFrame f = fit(camera, how);
    const glm::mat4 worldFromView = glm::inverse(viewFromWorld(camera));
    const float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
    float start = f.start, fitFrom = f.start;  // the previous cascade's blend band begins
    for (int c = 0; c < f.count; ++c) {
      for (float z : {fitFrom, f.ends[size_t(c)]}) {
        for (float sx : {-1.0f, 1.0f}) {
          for (float sy : {-1.0f, 1.0f}) {
            const glm::vec4 view(sx * z * tanHalf * 16.0f / 9.0f, sy * z * tanHalf, -z, 1.0f);
            const glm::vec2 p = glm::vec2(f.light.lightFromWorld * (worldFromView * view));
            const glm::vec2 uv = shaders::cascadeUv(p, f.boxes[size_t(c)], 0);
            // Corners lie on the tight box's edges: allow float rounding of the transform.
            EXPECT_GE(uv.x, -1e-4f) << c;
            EXPECT_LE(uv.x, 1.0f + 1e-4f) << c;
            EXPECT_GE(uv.y, -1e-4f) << c;
            EXPECT_LE(uv.y, 1.0f + 1e-4f) << c;
          }
        }
      }
      fitFrom = f.ends[size_t(c)] - f.blendBand * (f.ends[size_t(c)] - start);
      start = f.ends[size_t(c)];
    }
  }
}

TEST_F(CascadeFitTest, StabilizedBoxesKeepTheirSizeAndMoveByWholeTexelsAsTheCameraMoves) {
  const CascadeFrame a = fit(camera, CascadeFit::Stabilized);
  Camera moved = camera;
  moved.position += glm::vec3(0.37f, 0.0f, -0.81f);
  moved.target = moved.position + glm::vec3(5.0f, -0.4f, -30.0f);  // and turned
  const CascadeFrame b = fit(moved, CascadeFit::Stabilized);
  for (int c = 0; c < 4; ++c) {
    const glm::vec4 ba = a.boxes[size_t(c)], bb = b.boxes[size_t(c)];
    EXPECT_EQ(ba.z, bb.z) << c;  // size: exactly the same
    const float texel = ba.z / 1024.0f;
    const glm::vec2 shift = (glm::vec2(bb) - glm::vec2(ba)) / texel;
    // Whole texels, up to the rounding of snapped * texel - radius in float.
    EXPECT_NEAR(shift.x, std::round(shift.x), 1e-2f) << c;
    EXPECT_NEAR(shift.y, std::round(shift.y), 1e-2f) << c;
  }
  // The tight fit changes size as the camera turns: the shimmer stabilisation removes.
  const CascadeFrame ta = fit(camera, CascadeFit::Tight), tb = fit(moved, CascadeFit::Tight);
  EXPECT_NE(ta.boxes[0].z, tb.boxes[0].z);
}

TEST_F(CascadeFitTest, DefaultShadowDistanceCoversTheSceneFromAfarAndHoldsStill) {
  // The bounds' sphere: radius sqrt(100² + 5² + 100²) = 141.5, diameter 283.
  const float diameter = 2.0f * bounds.radius();
  // Inside the scene: one diameter reaches past its far side.
  EXPECT_FLOAT_EQ(defaultShadowDistance(camera, bounds), diameter);
  // Framed from 1000 away (a model's own camera): the far side lies at 1141.5, just past four
  // diameters (1132), so five.
  Camera afar = camera;
  afar.position = bounds.centre() + glm::vec3(0.0f, 0.0f, 1000.0f);
  EXPECT_FLOAT_EQ(defaultShadowDistance(afar, bounds), 5.0f * diameter);
  EXPECT_GT(defaultShadowDistance(afar, bounds), 1000.0f + bounds.radius());
  // A small move does not change it: stabilised cascades keep their sizes.
  afar.position.x += 0.5f;
  EXPECT_FLOAT_EQ(defaultShadowDistance(afar, bounds), 5.0f * diameter);
  CascadeSettings s;
  s.count = 2;
  EXPECT_FLOAT_EQ(fitCascades(s, afar, 1.5f, {0.05f, 5000.0f}, light, bounds, 256).ends[1],
                  5.0f * diameter);
}

TEST_F(CascadeFitTest, GivenSplitsOutsideTheShadowRangeAreRefusedWithTheRange) {
  CascadeSettings s;
  s.count = 3;
  s.maxDistance = 50.0f;
  s.distances = {10.0f, 60.0f};
  try {
    fitCascades(s, camera, 1.5f, {0.05f, 100.0f}, light, bounds, 256);
    FAIL() << "a split beyond the shadow distance accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("outside the shadow range (0.05, 50)"), std::string::npos)
        << e.what();
  }
  s.distances = {10.0f, 40.0f};
  EXPECT_FLOAT_EQ(fitCascades(s, camera, 1.5f, {0.05f, 100.0f}, light, bounds, 256).ends[2],
                  50.0f);
}

TEST(CascadeSettings, RefusesOutOfRangeValuesWithTheRange) {
  CascadeSettings s;
  s.count = 9;
  EXPECT_THROW(validateCascadeSettings(s), Error);
  s.count = 3;
  s.distances = {5.0f, 4.0f};
  try {
    validateCascadeSettings(s);
    FAIL() << "decreasing split distances accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("increasing"), std::string::npos) << e.what();
  }
  s.distances = {4.0f};
  EXPECT_THROW(validateCascadeSettings(s), Error) << "3 cascades need 2 distances";
  s.distances.clear();
  s.blendBand = 0.6f;
  EXPECT_THROW(validateCascadeSettings(s), Error);
}

TEST(CascadeBlur, KeepsTheKernelsWorldWidth) {
  // Cascade texels twice as wide: a 9-tap kernel (4.5 units of 0.5) becomes 5 taps of 1 unit
  // (nearest odd count to 4.5 rounds up), sigma halves.
  const BlurSpec b = cascadeBlur({BlurKernel::Gaussian, 4, 2.0f}, 0.5f);
  EXPECT_EQ(b.radius, 2);
  EXPECT_FLOAT_EQ(b.sigma, 1.0f);
  EXPECT_EQ(cascadeBlur({BlurKernel::Box, 2, 1.0f}, 1.0f).radius, 2);
}

}  // namespace
}  // namespace penumbra
