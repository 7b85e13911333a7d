// Float images.
#include "penumbra/image.h"

#include <algorithm>
#include <string>

#include "penumbra/error.h"

namespace penumbra {

Image::Image(int width, int height, int channels, float fill)
    : width_(width), height_(height), channels_(channels) {
  if (width <= 0 || height <= 0 || channels <= 0) {
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                std::to_string(channels) + " channels: all must be positive");
  }
  data_.assign(size_t(width) * size_t(height) * size_t(channels), fill);
}

float Image::clamped(int x, int y, int channel) const {
  return at(std::clamp(x, 0, width_ - 1), std::clamp(y, 0, height_ - 1), channel);
}

}  // namespace penumbra
