// glTF 2.0's JSON property types, checked before tinygltf reads the file: tinygltf skips a
// property of the wrong type silently (a mesh's primitives given as an object, a texture index
// of -1), which would render half a scene without a word.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace penumbra::scene {

// Checks the JSON of a .gltf, or the JSON chunk of a .glb (glbJsonChunk), against the types the
// glTF 2.0 schema gives the core properties (extension contents and extras are left to their
// readers). Throws Error "<name>: <path> must be ... (it is ...)".
void checkGltfJsonTypes(std::span<const uint8_t> text, const std::string& name);

}  // namespace penumbra::scene
