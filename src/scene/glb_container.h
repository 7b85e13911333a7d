// The binary glTF container (glTF 2.0 §4.4), checked before tinygltf reads it: tinygltf's own
// bounds check of the BIN chunk leaves out the chunk's 8-byte header, and a file whose BIN chunk
// ends up to 8 bytes past its end had it read past the buffer (found by the glTF fuzzer).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace penumbra::scene {

// Whether `bytes` starts with the GLB magic "glTF".
bool isGlb(std::span<const uint8_t> bytes);

// The JSON chunk of a GLB, after checking the header and that every chunk lies inside the
// length the header gives, which lies inside the file. Throws Error "<name>: <what is wrong>",
// with the byte the fault is at. Chunk alignment is left to tinygltf, which refuses a BIN chunk
// off a 4-byte boundary and reads a JSON chunk off one.
std::span<const uint8_t> glbJsonChunk(std::span<const uint8_t> bytes, const std::string& name);

}  // namespace penumbra::scene
