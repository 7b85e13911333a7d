// Channel layout and exact texture sizes.
#include "penumbra/channel_layout.h"

#include <algorithm>

namespace penumbra {

ChannelLayout channelLayout(Technique technique, const TechniqueParams& params) {
  ChannelLayout layout;
  layout.channels = channelCount(technique, params);
  layout.layers = (layout.channels + 3) / 4;
  layout.componentsPerTexel = layout.channels >= 3 ? 4 : layout.channels;
  layout.format = techniqueStorage(technique, params);
  return layout;
}

int mipLevelCount(int width, int height) {
  int levels = 1;
  for (int size = std::max(width, height); size > 1; size /= 2) ++levels;
  return levels;
}

uint64_t channelTextureBytes(const ChannelLayout& layout, int width, int height, bool withMips) {
  uint64_t bytes = 0;
  const int levels = withMips ? mipLevelCount(width, height) : 1;
  for (int level = 0; level < levels; ++level) {
    const uint64_t w = uint64_t(std::max(1, width >> level));
    const uint64_t h = uint64_t(std::max(1, height >> level));
    bytes += w * h * uint64_t(layout.layers) * uint64_t(layout.bytesPerTexel());
  }
  return bytes;
}

}  // namespace penumbra
