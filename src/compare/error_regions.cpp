// Largest-error windows: a summed-area table of |error| makes every window's sum O(1); windows
// are tried on a grid of a quarter window and chosen greedily, each apart from those before.
#include "penumbra/compare/error_regions.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace penumbra::compare {

std::vector<TroubleSpot> largestErrorRegions(const std::vector<Image>& errors, int count,
                                             float fraction) {
  if (errors.empty() || errors.front().empty() || count <= 0) return {};
  const int width = errors.front().width(), height = errors.front().height();
  // sums[(y) * (width + 1) + x]: |error| summed over [0, x) x [0, y).
  std::vector<double> sums(size_t(width + 1) * size_t(height + 1), 0.0);
  const auto at = [&](int x, int y) -> double& {
    return sums[size_t(y) * size_t(width + 1) + size_t(x)];
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double e = 0.0;
      for (const Image& error : errors) {
        const float v = error.at(x, y);
        if (std::isfinite(v)) e += std::abs(double(v));
      }
      at(x + 1, y + 1) = e + at(x, y + 1) + at(x + 1, y) - at(x, y);
    }
  }
  const int w = std::max(1, int(std::lround(fraction * float(width))));
  const int h = std::max(1, int(std::lround(fraction * float(height))));
  const int stepX = std::max(1, w / 4), stepY = std::max(1, h / 4);
  struct Window {
    int x, y;
    double sum;
  };
  std::vector<Window> windows;
  for (int y = 0;; y = std::min(y + stepY, height - h)) {
    for (int x = 0;; x = std::min(x + stepX, width - w)) {
      windows.push_back({x, y, at(x + w, y + h) - at(x, y + h) - at(x + w, y) + at(x, y)});
      if (x >= width - w) break;
    }
    if (y >= height - h) break;
  }
  std::stable_sort(windows.begin(), windows.end(),
                   [](const Window& a, const Window& b) { return a.sum > b.sum; });
  std::vector<Window> chosen;
  for (const Window& c : windows) {
    if (int(chosen.size()) == count || !(c.sum > 0.0)) break;
    const bool overlaps = std::any_of(chosen.begin(), chosen.end(), [&](const Window& o) {
      return std::abs(o.x - c.x) < w && std::abs(o.y - c.y) < h;
    });
    if (!overlaps) chosen.push_back(c);
  }
  std::vector<TroubleSpot> spots;
  for (const Window& c : chosen) {
    spots.push_back({"largest error " + std::to_string(spots.size() + 1),
                     {float(c.x) / float(width), float(c.y) / float(height),
                      float(c.x + w) / float(width), float(c.y + h) / float(height)}});
  }
  return spots;
}

}  // namespace penumbra::compare
