// Texture sampling as GL defines it, for the CPU reference: texel centres at (i + 0.5) / size,
// clamp-to-edge addressing, bilinear within a level and linear between levels.
#pragma once

#include <span>

#include "penumbra/image.h"

namespace penumbra {

// All channels at normalised coordinates (u, v); `out` holds image.channels() values.
void sampleBilinear(const Image& image, float u, float v, std::span<float> out);

// Trilinear: bilinear in levels floor(lod) and floor(lod)+1 of `mips`, blended by fract(lod);
// lod is clamped to [0, mips.size() - 1].
void sampleTrilinear(std::span<const Image> mips, float u, float v, float lod,
                     std::span<float> out);

}  // namespace penumbra
