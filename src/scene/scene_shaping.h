// What loadScene does to a scene file once its loader has read it: marks the geometry that
// encloses the rest, decides what casts shadows, adds a ground under a lone model and chooses the
// camera (SceneLoadOptions; docs/scenes.md, "Real models").
#pragma once

#include <string>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra::scene {

// Which meshes enclose the rest (a sky dome, a skybox), one flag per mesh, none where they do
// not all hold: they reach the top of the scene's bounds or span half their height; their
// vertices hug the bounds (a skybox) or stay outside what stands in the scene (a dome); together
// they reach the bounds' four sides and top above everything else, close the sky over it (rays
// up from the rest's centre all meet them) with faces turned to it (a body's legs turn theirs
// sideways); and something stands inside them (a mesh of the rest rising by a twentieth of its
// own largest extent: a house's walls and roof over its flat floor plate enclose nothing).
std::vector<bool> findEnclosures(const Scene& scene);

// True when an upward-facing surface at the bottom of the model's bounds covers a quarter of
// their footprint or more: the model stands on its own floor.
bool hasFloor(const Scene& scene);

// Throws Error "<source>: ..." for a camera index the file does not have.
void shapeFileScene(Scene& scene, const SceneLoadOptions& options, const std::string& source);

}  // namespace penumbra::scene
