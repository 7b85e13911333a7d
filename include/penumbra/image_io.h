// Image files: PNG through libpng (8-bit sRGB colour, 16-bit grey) and OpenEXR (float). Every
// writer refuses images holding NaN or Inf: they never reach an output file. Colour images hold
// linear light in memory; the colour PNG writers encode it to sRGB (penumbra/srgb.h), the only
// place penumbra does. Grey PNGs and EXRs hold data (visibility) and are written as they are.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "penumbra/image.h"

namespace penumbra {

// 3 or 4 channels of linear light in [0,1] (clamped), row 0 at the top: an 8-bit RGB PNG of their
// sRGB encoding, tagged sRGB. Alpha, if any, is dropped.
void writeColorPng(const Image& image, const std::filesystem::path& path);
// The 8-bit sRGB encoding writeColorPng stores (RGB interleaved, row 0 at the top), for showing
// on screen exactly what the file holds.
std::vector<uint8_t> encodeSrgb8(const Image& image);
// Already-encoded 8-bit sRGB pixels (width * height * 3, row 0 at the top) as a PNG tagged sRGB.
void writeEncodedColorPng(int width, int height, std::span<const uint8_t> rgb,
                          const std::filesystem::path& path);
// One channel in [0,1] (clamped): a 16-bit greyscale PNG.
void writeGrey16Png(const Image& image, const std::filesystem::path& path);
// One channel: a float OpenEXR image with channel "Y".
void writeFloatExr(const Image& image, const std::filesystem::path& path);

// Diagnostic images (RenderResult::diagnostic, -1 where nothing is drawn): a failure mask
// (failing pixels red over grey shading) and layer indices in distinct colours (thesis Fig. 4.2).
void writeFailureMaskPng(const Image& diagnostic, const Image& color,
                         const std::filesystem::path& path);
void writeLayerIndexPng(const Image& diagnostic, const Image& color,
                        const std::filesystem::path& path);

// Reads back what the writers above wrote (for tests and tools).
Image readGrey16Png(const std::filesystem::path& path);
// An 8-bit RGB PNG's samples as stored (sRGB-encoded, not decoded), each / 255: 3 channels.
Image readEncodedColorPng(const std::filesystem::path& path);
Image readFloatExr(const std::filesystem::path& path);

// Throws Error naming the first non-finite value's position.
void requireFinite(const Image& image, std::string_view what);

}  // namespace penumbra
