// glTF 2.0 scenes (.gltf with its buffers and images, .glb) through tinygltf.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "penumbra/scene.h"

namespace penumbra::scene {

// Parses a glTF 2.0 asset held in memory (JSON or GLB, told apart by the GLB magic). `name`
// names it in messages and becomes the scene's name. External buffers and images are read
// relative to `baseDirectory` when `readFiles` is set; otherwise every external URI is missing
// (the fuzzer's setting). Throws Error "<name>: <fault>" for anything malformed.
Scene loadGltf(std::span<const uint8_t> bytes, const std::string& name,
               const std::filesystem::path& baseDirectory, bool readFiles);

Scene loadGltfFile(const std::filesystem::path& path);

}  // namespace penumbra::scene
