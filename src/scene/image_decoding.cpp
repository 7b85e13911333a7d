// Texture decoding through stb_image, with the size checked before anything is allocated.
#include "image_decoding.h"

#include <climits>
#include <cstring>
#include <vector>

#include "stb_allocation_limit.h"
#include "stb_image.h"

namespace penumbra::scene {
namespace {

uint32_t bigEndian32(const uint8_t* p) {
  return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

// A PNG without its empty IDAT chunks. stb_image reads an empty first IDAT chunk by copying zero
// bytes into a buffer it has not allocated yet (memcpy to a null pointer: undefined behaviour,
// reported by UBSan; found by the glTF fuzzer). Empty IDAT chunks carry no data, and each chunk
// has its own CRC, so dropping them leaves the same image. Anything else is copied unchanged,
// including a truncated last chunk, for stb_image to judge.
std::vector<uint8_t> withoutEmptyPngDataChunks(std::span<const uint8_t> bytes) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0) {
    return {bytes.begin(), bytes.end()};
  }
  std::vector<uint8_t> out(bytes.begin(), bytes.begin() + 8);
  size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const uint64_t chunk = 12 + uint64_t(bigEndian32(&bytes[at]));  // length, type, data, CRC
    if (at + chunk > bytes.size()) break;
    const bool emptyData = chunk == 12 && std::memcmp(&bytes[at + 4], "IDAT", 4) == 0;
    if (!emptyData) out.insert(out.end(), bytes.begin() + at, bytes.begin() + at + chunk);
    at += size_t(chunk);
  }
  out.insert(out.end(), bytes.begin() + at, bytes.end());
  return out;
}

bool withinLimits(int width, int height) {
  return width > 0 && height > 0 && width <= kMaxTextureSide && height <= kMaxTextureSide &&
         int64_t(width) * int64_t(height) <= kMaxTextureTexels;
}

}  // namespace

std::optional<ImageSize> readImageSize(std::span<const uint8_t> bytes) {
  if (bytes.empty() || bytes.size() > size_t(INT_MAX)) return std::nullopt;
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels) ||
      !withinLimits(width, height)) {
    return std::nullopt;
  }
  return ImageSize{width, height};
}

std::optional<TextureImage> decodeImage(std::span<const uint8_t> original, const std::string& name,
                                        std::string& why) {
  const std::vector<uint8_t> bytes = withoutEmptyPngDataChunks(original);
  if (bytes.empty() || bytes.size() > size_t(INT_MAX)) {
    why = bytes.empty() ? "it is empty" : "it is larger than 2 GiB";
    return std::nullopt;
  }
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels)) {
    why = std::string("it is not an image stb_image can read (") + stbi_failure_reason() + ")";
    return std::nullopt;
  }
  if (!withinLimits(width, height)) {
    why = "its size " + std::to_string(width) + "x" + std::to_string(height) +
          " is beyond the largest texture accepted (" + std::to_string(kMaxTextureSide) +
          " per side, " + std::to_string(kMaxTextureTexels) + " texels)";
    return std::nullopt;
  }
  // What a decode of the declared size can need in one allocation: stb_image's widest buffer is
  // 16 bytes a texel (HDR's float RGBA before conversion; 16-bit PNG RGBA and its filter bytes
  // are 8), plus 1 MiB for its tables and first inflate buffer.
  const size_t texels = size_t(width) * size_t(height);
  stbAllocationLimit = {texels * 16 + size_t(height) * 16 + (size_t(1) << 20), false};
  stbi_uc* pixels =
      stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 4);
  const bool bomb = stbAllocationLimit.exceeded;
  stbAllocationLimit = {};
  if (pixels == nullptr) {
    why = bomb ? "decoding it needs more memory than its declared size " + std::to_string(width) +
                     "x" + std::to_string(height) +
                     " can (its compressed data expands beyond the image: a decompression bomb)"
               : std::string("decoding failed (") + stbi_failure_reason() + ")";
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
