// Texture decoding through stb_image, with the size checked before anything is allocated.
#include "image_decoding.h"

#include <climits>
#include <cstring>

#include "stb_image.h"

namespace penumbra::scene {

std::optional<TextureImage> decodeImage(std::span<const uint8_t> bytes, const std::string& name,
                                        std::string& why) {
  if (bytes.empty() || bytes.size() > size_t(INT_MAX)) {
    why = bytes.empty() ? "it is empty" : "it is larger than 2 GiB";
    return std::nullopt;
  }
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels)) {
    why = std::string("it is not an image stb_image can read (") + stbi_failure_reason() + ")";
    return std::nullopt;
  }
  if (width <= 0 || height <= 0 || width > kMaxTextureSide || height > kMaxTextureSide ||
      int64_t(width) * int64_t(height) > kMaxTextureTexels) {
    why = "its size " + std::to_string(width) + "x" + std::to_string(height) +
          " is beyond the largest texture accepted (" + std::to_string(kMaxTextureSide) +
          " per side, " + std::to_string(kMaxTextureTexels) + " texels)";
    return std::nullopt;
  }
  stbi_uc* pixels =
      stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 4);
  if (pixels == nullptr) {
    why = std::string("decoding failed (") + stbi_failure_reason() + ")";
    return std::nullopt;
  }
  TextureImage image;
  image.name = name;
  image.width = width;
  image.height = height;
  image.rgba.resize(size_t(width) * size_t(height) * 4);
  std::memcpy(image.rgba.data(), pixels, image.rgba.size());
  stbi_image_free(pixels);
  return image;
}

}  // namespace penumbra::scene
