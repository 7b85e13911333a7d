// Texture read-back.
#include "texture_readback.h"

#include <epoxy/gl.h>

#include <vector>

#include "penumbra/gl/context.h"

namespace penumbra::gl {

Image readTexture(unsigned texture, int level, int width, int height, int layers, int components,
                  unsigned format, bool flip) {
  std::vector<float> data(size_t(width) * size_t(height) * size_t(layers) * size_t(components));
  glGetTextureImage(texture, level, format, GL_FLOAT, GLsizei(data.size() * sizeof(float)),
                    data.data());
  checkErrors("reading back a texture");
  Image image(width, height, layers * components);
  for (int layer = 0; layer < layers; ++layer) {
    for (int y = 0; y < height; ++y) {
      const int row = flip ? height - 1 - y : y;
      for (int x = 0; x < width; ++x) {
        for (int c = 0; c < components; ++c) {
          image.at(x, row, layer * components + c) =
              data[((size_t(layer) * size_t(height) + size_t(y)) * size_t(width) + size_t(x)) *
                       size_t(components) +
                   size_t(c)];
        }
      }
    }
  }
  return image;
}

}  // namespace penumbra::gl
