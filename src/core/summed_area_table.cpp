// Summed-area tables in wrapping 64-bit fixed point (see the header for the error bound).
#include "penumbra/summed_area_table.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "parallel.h"
#include "penumbra/shared/summed_area.h"

namespace penumbra {

SummedAreaTable::SummedAreaTable(const Image& image)
    : width_(image.width()), height_(image.height()), channels_(image.channels()) {
  const size_t texels = size_t(width_) * size_t(height_);
  // Each channel's extremes fix its quantisation (shared/summed_area.h), as on the GPU.
  std::vector<shaders::SummedAreaQuantisation> quantisation(static_cast<size_t>(channels_));
  for (int c = 0; c < channels_; ++c) {
    float lo = std::numeric_limits<float>::infinity();
    float hi = -lo;
    for (size_t i = 0; i < texels; ++i) {
      const float v = image.data()[i * size_t(channels_) + size_t(c)];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    quantisation[size_t(c)] = shaders::summedAreaQuantisationFor(lo, hi);
  }
  centre_.resize(size_t(channels_));
  step_.resize(size_t(channels_));
  for (size_t c = 0; c < size_t(channels_); ++c) {
    centre_[c] = quantisation[c].centre;
    step_[c] = quantisation[c].step;
  }
  sums_.assign(texels * size_t(channels_), 0);
  // Row prefix sums in parallel, then column prefix sums; unsigned arithmetic wraps by design.
  // std::nearbyint in the default rounding mode rounds ties to even, as GLSL's roundEven does.
  detail::parallelForRows(height_, [&](int y) {
    for (int c = 0; c < channels_; ++c) {
      const shaders::SummedAreaQuantisation& q = quantisation[size_t(c)];
      const int64_t offset = int64_t(q.offset);
      uint64_t running = 0;
      for (int x = 0; x < width_; ++x) {
        const float units = shaders::summedAreaUnits(image.at(x, y, c), q);
        running += uint64_t(int64_t(std::nearbyint(units)) - offset);
        sums_[(size_t(y) * size_t(width_) + size_t(x)) * size_t(channels_) + size_t(c)] = running;
      }
    }
  });
  for (int y = 1; y < height_; ++y) {
    const size_t row = size_t(y) * size_t(width_) * size_t(channels_);
    const size_t above = row - size_t(width_) * size_t(channels_);
    for (size_t i = 0; i < size_t(width_) * size_t(channels_); ++i)
      sums_[row + i] += sums_[above + i];
  }
}

uint64_t SummedAreaTable::prefixSum(int x, int y, int channel) const {
  if (x < 0 || y < 0) return 0;
  return sums_[(size_t(y) * size_t(width_) + size_t(x)) * size_t(channels_) + size_t(channel)];
}

double SummedAreaTable::boxMean(int x0, int y0, int x1, int y1, int channel) const {
  assert(x0 <= x1 && y0 <= y1);
  x0 = std::clamp(x0, 0, width_ - 1);
  x1 = std::clamp(x1, 0, width_ - 1);
  y0 = std::clamp(y0, 0, height_ - 1);
  y1 = std::clamp(y1, 0, height_ - 1);
  const uint64_t wrapped = prefixSum(x1, y1, channel) - prefixSum(x0 - 1, y1, channel) -
                           prefixSum(x1, y0 - 1, channel) + prefixSum(x0 - 1, y0 - 1, channel);
  const double area = double(x1 - x0 + 1) * double(y1 - y0 + 1);
  return shaders::summedAreaMean(double(int64_t(wrapped)), area, step_[size_t(channel)],
                                 centre_[size_t(channel)]);
}

double SummedAreaTable::errorBound(int channel) const {
  // The mean is the box's fixed-point sum converted to double, divided by its area (within
  // 2^32 + 1 steps of the centre) and added to the centre: three roundings of 2^-53 of their
  // results each, covered by 2^-52 of the centre's magnitude and 2^33 steps.
  const double step = step_[size_t(channel)];
  const double magnitude = std::abs(centre_[size_t(channel)]) + 0x1p33 * step;
  return 0.5 * step + 0x1p-52 * magnitude;
}

}  // namespace penumbra
