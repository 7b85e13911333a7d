// What every file loader does once it has the meshes: checks the geometry, repairs bad normals,
// and gives the scene a camera and a light where the file has none.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra::scene {

// The camera and light a file asked for, if any.
struct FileView {
  std::vector<NamedCamera> cameras;
  std::optional<Light> light;
};

// Throws Error "<source>: ..." for an empty scene or non-finite positions or texture
// coordinates; replaces non-finite or zero normals by their triangles' normals (with a warning);
// keeps the file's cameras (Scene::fileCameras), sets the camera (the file's first, else one
// framing the bounds at 16:9; loadScene chooses again with the frame's aspect) and the light (from
// above) the file did not give.
void finishFileScene(Scene& scene, const std::string& source, const FileView& view);

// How a translucent (AlphaMode::Blend) material is drawn, for the loaders' warnings.
inline constexpr const char* kTranslucentMaterialRule =
    "its shadow lets through 1 - alpha (the light pass covers a dithered alpha share of the "
    "shadow map's texels, which filtering averages; the ray-traced truth attenuates exactly; "
    "techniques that cannot carry it draw a mask at 0.5, as the camera does)";

// Flat normals for triangles without normals: each triangle gets its own three vertices
// (glTF 2.0 §3.7.2.1: "client implementations MUST calculate flat normals").
void computeFlatNormals(Mesh& mesh);

}  // namespace penumbra::scene
