// Camera and light values from outside a scene are checked on their own (validateOverrides)
// before any loading: finite, within kMaxWorldCoordinate, angles in (0, 170].
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/cascades.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

TEST(SceneOverrides, VectorsStayWithinTheWorldRange) {
  const float bound = kMaxWorldCoordinate;
  const float beyond = std::nextafter(bound, INFINITY);
  SceneOverrides o;
  o.cameraPosition = glm::vec3(-bound, 0.0f, bound);
  o.lightDirection = glm::vec3(bound, -bound, bound);  // squared length 3e12: no overflow
  EXPECT_NO_THROW(validateOverrides(o));
  for (const glm::vec3 v : {glm::vec3(beyond, 0.0f, 0.0f), glm::vec3(0.0f, -beyond, 0.0f),
                            glm::vec3(0.0f, 0.0f, NAN)}) {
    SceneOverrides camera;
    camera.cameraTarget = v;
    EXPECT_THROW(validateOverrides(camera), Error);
    SceneOverrides light;
    light.lightPosition = v;
    EXPECT_THROW(validateOverrides(light), Error);
  }
  SceneOverrides huge;  // the repro: normalised, it became zero and lit nothing
  huge.lightDirection = glm::vec3(1e30f);
  EXPECT_THROW(validateOverrides(huge), Error);
}

TEST(SceneOverrides, AnglesOfZeroAreRefusedNotIgnored) {
  for (float degrees : {0.0f, -1.0f, 170.5f, NAN}) {
    SceneOverrides fov;
    fov.cameraFovDegrees = degrees;
    EXPECT_THROW(validateOverrides(fov), Error) << degrees;
    SceneOverrides spot;
    spot.spotAngleDegrees = degrees;
    EXPECT_THROW(validateOverrides(spot), Error) << degrees;
  }
  SceneOverrides widest;
  widest.cameraFovDegrees = 170.0f;
  widest.spotAngleDegrees = 170.0f;
  EXPECT_NO_THROW(validateOverrides(widest));
}

TEST(SceneOverrides, ShadowDistanceAndSplitsStayWithinTheWorldRange) {
  CascadeSettings s;
  s.count = 3;
  s.maxDistance = kMaxWorldCoordinate;
  s.distances = {10.0f, kMaxWorldCoordinate};
  EXPECT_NO_THROW(validateCascadeSettings(s));
  s.maxDistance = std::nextafter(kMaxWorldCoordinate, INFINITY);
  EXPECT_THROW(validateCascadeSettings(s), Error);
  s.maxDistance = 0.0f;
  s.distances = {10.0f, std::nextafter(kMaxWorldCoordinate, INFINITY)};
  EXPECT_THROW(validateCascadeSettings(s), Error);
}

}  // namespace
}  // namespace penumbra
