// GL-style bilinear and trilinear sampling.
#include "penumbra/sampling.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace penumbra {

void sampleBilinear(const Image& image, float u, float v, std::span<float> out) {
  assert(int(out.size()) >= image.channels());
  const float x = u * float(image.width()) - 0.5f;
  const float y = v * float(image.height()) - 0.5f;
  const int x0 = int(std::floor(x));
  const int y0 = int(std::floor(y));
  const float fx = x - float(x0);
  const float fy = y - float(y0);
  for (int c = 0; c < image.channels(); ++c) {
    const float top = (1.0f - fx) * image.clamped(x0, y0, c) + fx * image.clamped(x0 + 1, y0, c);
    const float bottom =
        (1.0f - fx) * image.clamped(x0, y0 + 1, c) + fx * image.clamped(x0 + 1, y0 + 1, c);
    out[size_t(c)] = (1.0f - fy) * top + fy * bottom;
  }
}

void sampleTrilinear(std::span<const Image> mips, float u, float v, float lod,
                     std::span<float> out) {
  assert(!mips.empty());
  const int last = int(mips.size()) - 1;
  lod = std::clamp(lod, 0.0f, float(last));
  const int level = std::min(int(std::floor(lod)), last);
  const int next = std::min(level + 1, last);
  const float t = lod - float(level);
  const size_t channels = size_t(mips[0].channels());
  std::vector<float> a(channels), b(channels);
  sampleBilinear(mips[size_t(level)], u, v, a);
  sampleBilinear(mips[size_t(next)], u, v, b);
  for (size_t c = 0; c < channels; ++c) out[c] = (1.0f - t) * a[c] + t * b[c];
}

}  // namespace penumbra
