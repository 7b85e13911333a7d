// Summed-area tables (Crow 1984; thesis §3.5 summed-area VSM) whose box means stay accurate at
// any size. Precision strategy: each channel is quantised to a 64-bit fixed-point integer with a
// power-of-two step in (R * 2^-32, R * 2^-31], R half the range (its largest deviation from the
// range's midpoint; R >= 2^-95, shared/summed_area.h has the ends), centred on the step's grid
// point at or below that midpoint; prefix sums wrap modulo 2^64, which leaves every box sum
// exact. The error is that quantisation and the double's rounding of the mean:
//   |boxMean - exact mean| <= R * 2^-32 + 2^-52 (|centre| + 4R)   for every box at every image
// size (about 2.3e-10 R while |centre| <= 2^20 R).
// The GPU's summed-area passes use the same integer scheme and reach the same bits
// (shared/summed_area.h).
#pragma once

#include <cstdint>
#include <vector>

#include "penumbra/image.h"

namespace penumbra {

class SummedAreaTable {
 public:
  explicit SummedAreaTable(const Image& image);

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }

  // Mean of channel `channel` over the inclusive texel box [x0,x1] x [y0,y1]; the box is clamped
  // to the image. Requires x0 <= x1 and y0 <= y1.
  double boxMean(int x0, int y0, int x1, int y1, int channel) const;

  // The guaranteed bound on |boxMean - exact mean| for a channel: half a step (<= R * 2^-32 where
  // R >= 2^-95) and the double's rounding of the mean, 2^-52 (|centre| + 2^33 steps).
  double errorBound(int channel) const;

  // The raw table, as the GPU's lookup reads it: the wrapping fixed-point sum over [0,x] x [0,y]
  // (0 if x or y < 0); a channel's value is centre + fixed * step.
  uint64_t prefixSum(int x, int y, int channel) const;
  double centre(int channel) const { return centre_[size_t(channel)]; }
  double step(int channel) const { return step_[size_t(channel)]; }

 private:
  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  std::vector<double> centre_;
  std::vector<double> step_;  // one fixed-point unit: a power of two <= R * 2^-31 if R > 0
  std::vector<uint64_t> sums_;
};

}  // namespace penumbra
