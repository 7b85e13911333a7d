// How a technique's channels are laid out in GPU memory, and the exact bytes that takes: one 2D
// array texture whose layers hold 4 channels each (1 or 2 when the technique has fewer), in the
// technique's storage format, optionally with a full mip chain.
#pragma once

#include <cstdint>

#include "penumbra/storage_format.h"
#include "penumbra/technique.h"

namespace penumbra {

struct ChannelLayout {
  int channels = 1;            // the technique's channel count
  int layers = 1;              // array layers: ceil(channels / 4)
  int componentsPerTexel = 1;  // 1, 2 or 4 (3 channels take 4: image formats have no RGB)
  StorageFormat format = StorageFormat::Float32;

  int bytesPerTexel() const { return componentsPerTexel * bytesPerChannel(format); }
};

ChannelLayout channelLayout(Technique technique, const TechniqueParams& params);

// floor(log2(max(w, h))) + 1: the GL mip chain down to 1x1.
int mipLevelCount(int width, int height);

// Bytes of a width x height texture of the layout, all mip levels included when `withMips`.
uint64_t channelTextureBytes(const ChannelLayout& layout, int width, int height, bool withMips);

}  // namespace penumbra
