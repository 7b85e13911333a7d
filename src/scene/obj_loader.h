// Wavefront OBJ scenes (with their .mtl materials, map_Kd colour and map_d alpha textures)
// through tinyobjloader.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "memory_budget.h"
#include "penumbra/scene.h"

namespace penumbra::scene {

// Reads a file the OBJ names (a material library, a texture) by its name as written; `what` says
// which in messages ("texture 'bark.png'"). Nothing when it cannot be read; throws Error to
// refuse it (not a regular file, beyond the memory budget).
using ObjFileReader = std::function<std::optional<std::vector<uint8_t>>(const std::string& name,
                                                                        const std::string& what)>;

// Parses OBJ text; `name` names it in messages and becomes the scene's name. Geometry and decoded
// textures are charged to `budget` (and checked) before they are built; every texture file is
// read and decoded once. Throws Error "<name>: <fault>" for indices out of range, non-finite
// values, no triangles, a file the reader refuses, or a scene the budget cannot hold.
Scene loadObj(const std::string& objText, const std::string& name, const ObjFileReader& readFile,
              MemoryBudget& budget);

// Reads the file, its material libraries and textures relative to its folder (regular files only,
// charged to `budget`).
Scene loadObjFile(const std::filesystem::path& path, MemoryBudget& budget);

}  // namespace penumbra::scene
