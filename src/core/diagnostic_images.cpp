// Heat-map palette, failure mask and layer colours.
#include "penumbra/diagnostic_images.h"

#include <algorithm>

namespace penumbra {
namespace {

constexpr ErrorPaletteStop kErrorPalette[] = {{-1.0f, 0x21, 0x66, 0xac},
                                              {-0.5f, 0x92, 0xc5, 0xde},
                                              {0.0f, 0xf7, 0xf7, 0xf7},
                                              {0.5f, 0xf4, 0xa5, 0x82},
                                              {1.0f, 0xb2, 0x18, 0x2b}};

glm::vec3 stopColour(const ErrorPaletteStop& s) {
  return glm::vec3(s.red, s.green, s.blue) / 255.0f;
}

}  // namespace

std::span<const ErrorPaletteStop> errorPalette() {
  return kErrorPalette;
}

glm::vec3 errorHeatColour(float error, float range) {
  const float t = range > 0.0f ? std::clamp(error / range, -1.0f, 1.0f) : 0.0f;
  for (size_t i = 1; i < std::size(kErrorPalette); ++i) {
    const ErrorPaletteStop& a = kErrorPalette[i - 1];
    const ErrorPaletteStop& b = kErrorPalette[i];
    if (t <= b.position) {
      return glm::mix(stopColour(a), stopColour(b), (t - a.position) / (b.position - a.position));
    }
  }
  return stopColour(kErrorPalette[std::size(kErrorPalette) - 1]);
}

Image failureMaskImage(const Image& diagnostic, const Image& color) {
  Image out(diagnostic.width(), diagnostic.height(), 3);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      const float d = diagnostic.at(x, y);
      const float grey = 0.5f * (color.at(x, y, 0) + color.at(x, y, 1) + color.at(x, y, 2)) / 3.0f;
      const bool failed = d > 0.5f;
      out.at(x, y, 0) = d < 0.0f ? 0.0f : (failed ? 1.0f : grey);
      out.at(x, y, 1) = d < 0.0f ? 0.0f : (failed ? 0.1f : grey);
      out.at(x, y, 2) = d < 0.0f ? 0.0f : (failed ? 0.1f : grey);
    }
  }
  return out;
}

Image layerIndexImage(const Image& diagnostic, const Image& color) {
  static const float palette[8][3] = {{0.9f, 0.3f, 0.3f}, {0.3f, 0.8f, 0.3f}, {0.3f, 0.4f, 0.9f},
                                      {0.9f, 0.8f, 0.2f}, {0.8f, 0.3f, 0.8f}, {0.2f, 0.8f, 0.8f},
                                      {0.9f, 0.6f, 0.3f}, {0.6f, 0.6f, 0.6f}};
  Image out(diagnostic.width(), diagnostic.height(), 3);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      const float d = diagnostic.at(x, y);
      const float shade = 0.4f + 0.6f * color.at(x, y, 1);
      for (int c = 0; c < 3; ++c) {
        out.at(x, y, c) = d < 0.0f ? 0.0f : shade * palette[int(d) % 8][c];
      }
    }
  }
  return out;
}

}  // namespace penumbra
