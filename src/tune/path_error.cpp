// tune's objectives over camera-path frames (path_error.h).
#include "path_error.h"

#include <cmath>
#include <span>

#include "penumbra/metrics.h"

namespace penumbra::tune {
namespace {

// Squared errors of one frame, plain and leak-weighted, and their pixel count.
struct FrameSums {
  double squared = 0.0;
  double weighted = 0.0;
  long pixels = 0;
};

FrameSums frameSums(const Image& visibility, const FrameTarget& target, double leakWeight) {
  FrameSums s;
  const auto& v = visibility.data();
  const auto& t = target.visibility.data();
  const auto& m = target.mask.data();
  for (size_t i = 0; i < m.size(); ++i) {
    if (!(m[i] > 0.5f)) continue;
    const double e = double(v[i]) - double(t[i]);
    s.squared += e * e;
    s.weighted += (e > 0.0 ? leakWeight : 1.0) * e * e;  // e > 0: lighter than the target
    ++s.pixels;
  }
  return s;
}

}  // namespace

SetError errorOver(ErrorMeasure measure, double leakWeight, const std::vector<Image>& visibility,
                   const PathTargets& targets, size_t first, size_t last) {
  double squared = 0.0, weighted = 0.0;
  long pixels = 0;
  for (size_t f = first; f < last; ++f) {
    const FrameSums s = frameSums(visibility[f], targets.frames[f], leakWeight);
    squared += s.squared;
    weighted += s.weighted;
    pixels += s.pixels;
  }
  SetError e;
  e.rmse = std::sqrt(squared / double(pixels));
  switch (measure) {
    case ErrorMeasure::Rmse: e.measure = e.rmse; break;
    case ErrorMeasure::LeakWeighted: e.measure = std::sqrt(weighted / double(pixels)); break;
    case ErrorMeasure::Flicker: {
      std::vector<Image> truths, masks;
      for (size_t f = first; f < last; ++f) {
        truths.push_back(targets.frames[f].visibility);
        masks.push_back(targets.frames[f].mask);
      }
      const std::span<const Image> estimates(visibility.data() + first, last - first);
      e.measure = e.rmse + temporalFlicker(estimates, truths, masks);
      break;
    }
  }
  return e;
}

}  // namespace penumbra::tune
