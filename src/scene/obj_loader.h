// Wavefront OBJ scenes (with their .mtl materials, map_Kd colour and map_d alpha textures)
// through tinyobjloader.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra::scene {

// Reads a file a material names (its .mtl library, textures) by its name as written; nothing
// when it cannot be read.
using ObjFileReader = std::function<std::optional<std::vector<uint8_t>>(const std::string& name)>;

// Parses OBJ text; `name` names it in messages and becomes the scene's name. Throws Error
// "<name>: <fault>" for indices out of range, non-finite values or no triangles.
Scene loadObj(const std::string& objText, const std::string& name, const ObjFileReader& readFile);

// Reads material libraries and textures relative to the file's folder.
Scene loadObjFile(const std::filesystem::path& path);

}  // namespace penumbra::scene
