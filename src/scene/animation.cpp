// Orbit, dolly and light-sweep animations.
#include "penumbra/animation.h"

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr std::string_view kNames[] = {"orbit", "dolly", "light", "clip"};

glm::vec3 turnAboutVertical(glm::vec3 v, float radians) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), radians, glm::vec3(0.0f, 1.0f, 0.0f)) *
                   glm::vec4(v, 0.0f));
}

}  // namespace

Animation parseAnimation(std::string_view name) {
  for (size_t i = 0; i < std::size(kNames); ++i) {
    if (name == kNames[i]) return Animation(i);
  }
  throw Error("unknown animation '" + std::string(name) +
              "'; valid animations: " + animationNameList());
}

std::string animationNameList() {
  std::string list;
  for (std::string_view n : kNames) list += (list.empty() ? "" : ", ") + std::string(n);
  return list;
}

std::vector<Animation> defaultAnimations(const Scene& scene) {
  return {scene.animation.moves() ? Animation::Clip : Animation::Orbit};
}

AnimatedView animatedView(const Scene& scene, std::span<const Animation> animations, int frame,
                          int frames) {
  const float t = frames > 0 ? float(frame) / float(frames) : 0.0f;
  const float turn = glm::two_pi<float>() * t;
  AnimatedView view{scene.camera, scene.light};
  for (Animation a : animations) {
    switch (a) {
      case Animation::Orbit:
        view.camera.position =
            view.camera.target + turnAboutVertical(view.camera.position - view.camera.target, turn);
        break;
      case Animation::Dolly:
        view.camera.position += 0.5f * t * (view.camera.target - view.camera.position);
        break;
      case Animation::LightSweep:
        view.light.direction = turnAboutVertical(view.light.direction, turn);
        view.light.position =
            view.light.target + turnAboutVertical(view.light.position - view.light.target, turn);
        break;
      case Animation::Clip: break;
    }
  }
  return view;
}

}  // namespace penumbra
