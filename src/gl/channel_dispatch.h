// What every compute pass over channel textures does the same way: 8x8 groups, the format's
// image qualifier as CHANNEL_FORMAT, the channel image at binding 0, square sizes as ivec2.
#pragma once

#include <vector>

#include "penumbra/channel_layout.h"
#include "penumbra/gl/program.h"
#include "program_cache.h"

namespace penumbra::gl {

inline constexpr unsigned kChannelGroup = 8;

inline unsigned groups(int n, unsigned size) {
  return (unsigned(n) + size - 1) / size;
}

std::vector<ShaderDefine> formatDefines(const ChannelLayout& layout);
// How the blur and mip passes reduce the channels, resolved at compile time where possible
// (src/shaders/lib/layer_reduction.glsl): ALL_MEAN, or a one-layer LAYER_REDUCTIONS table.
std::vector<ShaderDefine> reductionDefines(Technique technique, const TechniqueParams& params,
                                           const ChannelLayout& layout);
void bindChannelImage(const Texture& texture, const ChannelLayout& layout, int level);
void setSize(const Program& p, const char* name, int size);

}  // namespace penumbra::gl
