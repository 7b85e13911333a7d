// What loadScene does to a scene file once its loader has read it: marks the geometry that
// encloses the rest, decides what casts shadows, adds a ground under a lone model and chooses the
// camera (SceneLoadOptions; docs/scenes.md, "Real models").
#pragma once

#include <string>

#include "penumbra/scene.h"

namespace penumbra::scene {

// Meshes that reach the top of the scene's bounds or span half their height, whose vertices hug
// the bounds (a skybox) or stay outside what stands in the scene (a dome), and that together
// reach the bounds' four sides and top above everything else and close the sky over it (rays
// up from the rest's centre all meet them) with faces turned to it (a body's legs turn theirs
// sideways): a sky dome, a skybox.
void markEnclosures(Scene& scene);

// True when an upward-facing surface at the bottom of the model's bounds covers a quarter of
// their footprint or more: the model stands on its own floor.
bool hasFloor(const Scene& scene);

// Throws Error "<source>: ..." for a camera index the file does not have.
void shapeFileScene(Scene& scene, const SceneLoadOptions& options, const std::string& source);

}  // namespace penumbra::scene
