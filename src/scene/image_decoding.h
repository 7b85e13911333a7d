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

// What an image decodes to, from its header.
struct ImageSize {
  int width = 0;
  int height = 0;
  uint64_t rgbaBytes() const { return uint64_t(width) * uint64_t(height) * 4; }
};

// The size an image's header declares, read without decoding (for the memory budget); nothing
// when stb_image cannot read the header or the size is beyond the limits above (decodeImage then
// refuses it too).
std::optional<ImageSize> readImageSize(std::span<const uint8_t> bytes);

// Decodes to RGBA8 (row 0 at the top). On failure returns nothing and says why in `why`.
std::optional<TextureImage> decodeImage(std::span<const uint8_t> bytes, const std::string& name,
                                        std::string& why);

}  // namespace penumbra::scene
