// Texture read-back.
#include "texture_readback.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

#include "penumbra/gl/context.h"

namespace penumbra::gl {

Image readTexture(unsigned texture, int level, int width, int height, int layers, int components,
                  unsigned format, bool flip) {
  Image image(width, height, layers * components);
  const size_t rowFloats = size_t(width) * size_t(components);
  if (layers == 1) {
    // GL's layout is the image's: read straight into it, then turn the rows over in place.
    glGetTextureImage(texture, level, format, GL_FLOAT,
                      GLsizei(image.data().size() * sizeof(float)), image.data().data());
    checkErrors("reading back a texture");
    if (flip) {
      float* rows = image.data().data();
      for (int y = 0; y < height / 2; ++y) {
        std::swap_ranges(rows + size_t(y) * rowFloats, rows + size_t(y + 1) * rowFloats,
                         rows + size_t(height - 1 - y) * rowFloats);
      }
    }
    return image;
  }
  // Layers one after another in GL; the image interleaves them per texel.
  std::vector<float> data(size_t(height) * rowFloats * size_t(layers));
  glGetTextureImage(texture, level, format, GL_FLOAT, GLsizei(data.size() * sizeof(float)),
                    data.data());
  checkErrors("reading back a texture");
  for (int layer = 0; layer < layers; ++layer) {
    for (int y = 0; y < height; ++y) {
      const int row = flip ? height - 1 - y : y;
      const float* source = data.data() + (size_t(layer) * size_t(height) + size_t(y)) * rowFloats;
      for (int x = 0; x < width; ++x) {
        for (int c = 0; c < components; ++c) {
          image.at(x, row, layer * components + c) =
              source[size_t(x) * size_t(components) + size_t(c)];
        }
      }
    }
  }
  return image;
}

}  // namespace penumbra::gl
