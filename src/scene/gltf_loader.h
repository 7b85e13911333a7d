// glTF 2.0 scenes (.gltf with its buffers and images, .glb) through tinygltf.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "memory_budget.h"
#include "penumbra/scene.h"

namespace penumbra::scene {

// Parses a glTF 2.0 asset held in memory (JSON or GLB, told apart by the GLB magic). `name`
// names it in messages and becomes the scene's name. External buffers and images are read
// relative to `baseDirectory` when `readFiles` is set; otherwise every external URI is missing
// (the fuzzer's setting). External files, geometry and decoded textures are charged to `budget`
// (the scene file's own bytes are the caller's to charge). Throws Error "<name>: <fault>" for
// anything malformed, a hierarchy deeper than kMaxGltfNodeDepth, a file named that is not a
// regular file, and a scene the budget cannot hold.
Scene loadGltf(std::span<const uint8_t> bytes, const std::string& name,
               const std::filesystem::path& baseDirectory, bool readFiles, MemoryBudget& budget);

// Reads the file (charged to `budget`) and loads it with the files it names.
Scene loadGltfFile(const std::filesystem::path& path, MemoryBudget& budget);

}  // namespace penumbra::scene
