// Frame-sequence animations.
#include <gtest/gtest.h>

#include "penumbra/animation.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

TEST(Animation, OrbitKeepsDistanceAndHeightAndReachesTheFarSideHalfWay) {
  const Scene scene = makeBuiltinScene("backyard");
  const Animation orbit[] = {Animation::Orbit};
  const AnimatedView start = animatedView(scene, orbit, 0, 8);
  const AnimatedView half = animatedView(scene, orbit, 4, 8);
  EXPECT_EQ(start.camera.position, scene.camera.position) << "frame 0 is the scene's view";
  const glm::vec3 a = scene.camera.position - scene.camera.target;
  const glm::vec3 b = half.camera.position - half.camera.target;
  // Rotation by pi in float: a few ulp of the offset's length.
  EXPECT_NEAR(glm::length(b), glm::length(a), 1e-4f);
  EXPECT_NEAR(b.y, a.y, 1e-5f);
  EXPECT_NEAR(b.x, -a.x, 1e-4f);
  EXPECT_NEAR(b.z, -a.z, 1e-4f);
}

TEST(Animation, DollyHalvesTheDistanceAndLightSweepKeepsTheElevation) {
  const Scene scene = makeBuiltinScene("backyard");
  const Animation both[] = {Animation::Dolly, Animation::LightSweep};
  const AnimatedView v = animatedView(scene, both, 3, 4);  // t = 3/4
  const float before = glm::length(scene.camera.target - scene.camera.position);
  EXPECT_NEAR(glm::length(v.camera.target - v.camera.position), before * (1.0f - 0.375f), 1e-4f);
  EXPECT_NEAR(v.light.direction.y, scene.light.direction.y, 1e-6f);
  EXPECT_GT(glm::length(v.light.direction - scene.light.direction), 0.1f) << "the light turned";
  EXPECT_THROW(parseAnimation("spin"), Error);
}

}  // namespace
}  // namespace penumbra
