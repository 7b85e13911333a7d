// Visibility error metrics.
#include "penumbra/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "penumbra/error.h"

namespace penumbra {
namespace {

void requireSameShape(const Image& a, const Image& b, const char* what) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() != 1 ||
      b.channels() != 1) {
    throw Error(std::string(what) + ": images must be one-channel and of one size (" +
                std::to_string(a.width()) + "x" + std::to_string(a.height()) + " vs " +
                std::to_string(b.width()) + "x" + std::to_string(b.height()) + ")");
  }
}

}  // namespace

VisibilityErrors measureVisibilityErrors(const Image& estimate, const Image& reference,
                                         const Image& mask, double tau) {
  requireSameShape(estimate, reference, "visibility errors");
  requireSameShape(estimate, mask, "visibility errors");
  VisibilityErrors e;
  double squares = 0.0, absolutes = 0.0, leakSum = 0.0, darkSum = 0.0;
  int leaks = 0, darks = 0;
  for (int y = 0; y < estimate.height(); ++y) {
    for (int x = 0; x < estimate.width(); ++x) {
      if (mask.at(x, y) <= 0.5f) continue;
      const double difference = double(estimate.at(x, y)) - double(reference.at(x, y));
      ++e.pixels;
      if (!std::isfinite(difference)) {
        if (e.nonFinitePixels++ == 0) {
          e.worstX = x;
          e.worstY = y;
        }
        continue;
      }
      squares += difference * difference;
      absolutes += std::abs(difference);
      if (std::abs(difference) > e.maxAbsolute && e.nonFinitePixels == 0) {
        e.maxAbsolute = std::abs(difference);
        e.worstX = x;
        e.worstY = y;
      }
      if (difference > tau) {
        ++leaks;
        leakSum += difference;
      } else if (difference < -tau) {
        ++darks;
        darkSum -= difference;
      }
    }
  }
  if (e.pixels == 0) return e;
  const double n = double(e.pixels);
  e.rmse = std::sqrt(squares / n);
  e.meanAbsolute = absolutes / n;
  if (e.nonFinitePixels > 0) {
    e.rmse = e.meanAbsolute = e.maxAbsolute = std::numeric_limits<double>::quiet_NaN();
  }
  e.psnr = std::isnan(e.rmse) ? e.rmse
           : e.rmse > 0.0     ? std::min(100.0, 20.0 * std::log10(1.0 / e.rmse))
                              : 100.0;
  e.leakShare = leaks / n;
  e.leakMeanExcess = leaks > 0 ? leakSum / leaks : 0.0;
  e.darkShare = darks / n;
  e.darkMeanExcess = darks > 0 ? darkSum / darks : 0.0;
  return e;
}

namespace {

// mean_t mean_p |(v_t - v_{t-1}) - (r_t - r_{t-1})| over pixels covered in both frames; without
// references, r = 0.
double meanFrameStep(std::span<const Image> estimates, std::span<const Image> references,
                     std::span<const Image> masks, const char* what) {
  const bool referenced = !references.empty();
  if (estimates.size() < 2 || (referenced && estimates.size() != references.size()) ||
      estimates.size() != masks.size()) {
    throw Error(std::string(what) + " needs two or more frames, with " +
                (referenced ? "a reference and " : "") + "a mask for each");
  }
  double change = 0.0;
  size_t pixels = 0;
  for (size_t t = 1; t < estimates.size(); ++t) {
    requireSameShape(estimates[t], estimates[t - 1], what);
    requireSameShape(estimates[t], masks[t], what);
    if (referenced) requireSameShape(estimates[t], references[t], what);
    for (size_t i = 0; i < estimates[t].data().size(); ++i) {
      if (masks[t].data()[i] <= 0.5f || masks[t - 1].data()[i] <= 0.5f) continue;
      const double estimateStep = double(estimates[t].data()[i]) - estimates[t - 1].data()[i];
      const double referenceStep =
          referenced ? double(references[t].data()[i]) - references[t - 1].data()[i] : 0.0;
      change += std::abs(estimateStep - referenceStep);
      ++pixels;
    }
  }
  return pixels == 0 ? 0.0 : change / double(pixels);
}

}  // namespace

double temporalFlicker(std::span<const Image> estimates, std::span<const Image> references,
                       std::span<const Image> masks) {
  if (references.empty()) {
    throw Error("temporal flicker needs two or more frames, with a reference and a mask for each");
  }
  return meanFrameStep(estimates, references, masks, "temporal flicker");
}

double frameToFrameChange(std::span<const Image> estimates, std::span<const Image> masks) {
  return meanFrameStep(estimates, {}, masks, "frame-to-frame change");
}

Image signedVisibilityError(const Image& visibility, const Image& reference,
                            const Image& coverage) {
  Image error(visibility.width(), visibility.height(), 1);
  for (size_t i = 0; i < error.data().size(); ++i) {
    error.data()[i] = coverage.data()[i] > 0.5f ? visibility.data()[i] - reference.data()[i] : 0.0f;
  }
  return error;
}

Image litSurfaceMask(const Image& lookup) {
  if (lookup.channels() != 4) {
    throw Error("the lit-surface mask needs the frame's lookup image (4 channels, got " +
                std::to_string(lookup.channels()) +
                "): render the frame with RenderSettings::lookupInputs");
  }
  Image mask(lookup.width(), lookup.height(), 1);
  for (int y = 0; y < lookup.height(); ++y) {
    for (int x = 0; x < lookup.width(); ++x)
      mask.at(x, y) = lookup.at(x, y, 3) > 0.75f ? 1.0f : 0.0f;
  }
  return mask;
}

double median(std::vector<double> values) {
  if (values.empty()) throw Error("the median of no values");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace penumbra
