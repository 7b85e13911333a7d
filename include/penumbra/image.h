// A float image of 1..N interleaved channels, row-major with (0,0) the first texel: the CPU
// counterpart of a shadow-map texture.
#pragma once

#include <span>
#include <vector>

namespace penumbra {

class Image {
 public:
  Image() = default;
  // Throws Error unless width, height and channels are all positive.
  Image(int width, int height, int channels, float fill = 0.0f);

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  bool empty() const { return data_.empty(); }

  float& at(int x, int y, int channel = 0) { return data_[index(x, y, channel)]; }
  float at(int x, int y, int channel = 0) const { return data_[index(x, y, channel)]; }
  // The texel at (x, y) clamped to the image (GL's clamp-to-edge).
  float clamped(int x, int y, int channel = 0) const;

  std::span<float> data() { return data_; }
  std::span<const float> data() const { return data_; }

 private:
  size_t index(int x, int y, int channel) const {
    return (size_t(y) * size_t(width_) + size_t(x)) * size_t(channels_) + size_t(channel);
  }

  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  std::vector<float> data_;
};

}  // namespace penumbra
