// The scene's vertex and index buffers as the renderer uploads them (one 32-byte Vertex each,
// 32-bit indices), and the largest buffer a GL draws from: checked before the upload.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace penumbra::gl {

// Software rasterisers (llvmpipe, softpipe) address a buffer with signed 32-bit offsets: they
// crash drawing from a larger one, and say nothing when it is created.
inline constexpr uint64_t kSoftwareRasterizerMaxBufferBytes = (uint64_t(1) << 31) - 1;

// Why the GL named `device` (GL_RENDERER) cannot draw a scene of `vertices` vertices and
// `indices` indices from its buffers, or "" where it can.
std::string sceneBufferShortfall(uint64_t vertices, uint64_t indices, std::string_view device);

}  // namespace penumbra::gl
