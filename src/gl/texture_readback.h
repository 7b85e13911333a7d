// Reading GL textures back into Images.
#pragma once

#include "penumbra/image.h"

namespace penumbra::gl {

// A level of a texture (row 0 at the bottom) as an Image with layers x components channels,
// optionally flipped to row 0 at the top.
Image readTexture(unsigned texture, int level, int width, int height, int layers, int components,
                  unsigned format, bool flip);

}  // namespace penumbra::gl
