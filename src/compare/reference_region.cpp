// The filtered reference's kernel at a pixel as a depth distribution.
#include "penumbra/compare/reference_region.h"

#include <algorithm>
#include <cmath>

#include "penumbra/filters.h"

namespace penumbra::compare {

std::vector<DepthSample> referenceRegion(const Image& depth, const Image& lookup,
                                         const Image& plane, int x, int y, const BlurSpec& blur) {
  const std::vector<float> weights = blurWeights(blur);
  const int r = int(weights.size() / 2);
  const int size = depth.width();
  const double px = double(lookup.at(x, y, 0)) * size, py = double(lookup.at(x, y, 1)) * size;
  const double gx = plane.at(x, y, 0), gy = plane.at(x, y, 1);
  const double bx = std::floor(px - 0.5), by = std::floor(py - 0.5);
  const double fx = px - 0.5 - bx, fy = py - 0.5 - by;
  std::vector<DepthSample> region;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const double w = (i == 0 ? 1 - fx : fx) * (j == 0 ? 1 - fy : fy);
      if (w <= 0.0) continue;
      for (int b = -r; b <= r; ++b) {
        for (int a = -r; a <= r; ++a) {
          const int tx = int(bx) + i + a, ty = int(by) + j + b;
          const double offset = gx * (tx + 0.5 - px) + gy * (ty + 0.5 - py);
          const double z = double(depth.clamped(tx, ty)) - offset;
          const double weight = w * weights[size_t(a + r)] * weights[size_t(b + r)];
          if (weight > 0.0) region.push_back({float(std::clamp(z, 0.0, 1.0)), float(weight)});
        }
      }
    }
  }
  return region;
}

}  // namespace penumbra::compare
