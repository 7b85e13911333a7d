// GL internal formats and GLSL image format qualifiers for channel layouts.
#pragma once

#include <string>

#include "penumbra/channel_layout.h"

namespace penumbra::gl {

unsigned internalFormat(const ChannelLayout& layout);           // e.g. GL_RG32F, GL_RGBA16
std::string imageFormatQualifier(const ChannelLayout& layout);  // e.g. "rg32f", "rgba16"

}  // namespace penumbra::gl
