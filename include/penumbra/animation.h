// Camera and light animations for frame sequences (`penumbra render --frames N`): the way to
// look at flicker and shimmering.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra {

enum class Animation {
  Orbit,       // the camera circles its target once, at its height and distance
  Dolly,       // the camera moves toward its target, to half the distance
  LightSweep,  // the light turns once about the vertical through the scene (elevation kept)
  Clip,        // the scene file's own animation plays once (clipTime, poseScene)
};

// "orbit", "dolly", "light", "clip"; throws Error listing the valid names.
Animation parseAnimation(std::string_view name);
std::string animationNameList();

// What --frames plays when no animation is named: the scene's clip where it has one that moves,
// else the orbit.
std::vector<Animation> defaultAnimations(const Scene& scene);

// The view of frame `frame` of `frames` (frame 0 is the scene's own view): every animation in
// the list applied at time t = frame / frames (Clip moves the geometry, not the view: poseScene).
struct AnimatedView {
  Camera camera;
  Light light;
};
AnimatedView animatedView(const Scene& scene, std::span<const Animation> animations, int frame,
                          int frames);

}  // namespace penumbra
