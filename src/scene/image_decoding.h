// Texture images from encoded bytes (PNG, JPEG, ... through stb_image) for the scene loaders.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "penumbra/scene.h"

namespace penumbra::scene {

// The largest texture the loaders accept, per side and in texels: a few bytes of header can ask
// stb_image for gigabytes, and no GL takes a side beyond 16384.
inline constexpr int kMaxTextureSide = 16384;
inline constexpr int64_t kMaxTextureTexels = int64_t(1) << 26;

// Decodes to RGBA8 (row 0 at the top). On failure returns nothing and says why in `why`.
std::optional<TextureImage> decodeImage(std::span<const uint8_t> bytes, const std::string& name,
                                        std::string& why);

}  // namespace penumbra::scene
