// Error metrics of a visibility image against a reference (docs/reference.md says which
// reference each report column uses). Only covered pixels count: mask > 0.5.
#pragma once

#include <span>
#include <vector>

#include "penumbra/image.h"

namespace penumbra {

struct VisibilityErrors {
  int pixels = 0;  // covered pixels compared
  // Covered pixels where v or r is not a finite number. Any makes rmse, meanAbsolute,
  // maxAbsolute and psnr NaN (an error that cannot be measured is not a small one), and the worst
  // pixel is the first of them.
  int nonFinitePixels = 0;
  double rmse = 0.0;          // sqrt(mean (v - r)^2)
  double meanAbsolute = 0.0;  // mean |v - r|
  double maxAbsolute = 0.0;   // max |v - r|
  double psnr = 0.0;          // 20 log10(1 / rmse), dB, for the visibility range 1; 100 when exact
  double leakShare = 0.0;     // share of pixels with v > r + tau: light leaking
  double leakMeanExcess = 0.0;  // mean (v - r) over those pixels (0 when none)
  double darkShare = 0.0;       // share with v < r - tau: over-darkening
  double darkMeanExcess = 0.0;  // mean (r - v) over those pixels (0 when none)
  int worstX = -1;              // the pixel of the largest |v - r|
  int worstY = -1;
};

// Both images one channel, same size as the mask; throws Error otherwise.
VisibilityErrors measureVisibilityErrors(const Image& estimate, const Image& reference,
                                         const Image& mask, double tau = 0.05);

// Temporal flicker along a camera path: the mean frame-to-frame change of the estimate's
// visibility beyond the reference's own change, over pixels covered in both frames:
//   mean_t mean_p |(v_t - v_{t-1}) - (r_t - r_{t-1})|.
// Needs at least two frames; all images one channel and of one size.
double temporalFlicker(std::span<const Image> estimates, std::span<const Image> references,
                       std::span<const Image> masks);

// Shimmer along a camera path: the mean frame-to-frame change of the visibility itself,
//   mean_t mean_p |v_t - v_{t-1}|,
// over pixels covered in both frames. Along a path of sub-pixel camera steps the true shadows
// barely move, so what is left is the shadow map's own instability; comparing two settings on
// one path (stabilised against tight cascades) isolates it. Needs at least two frames.
double frameToFrameChange(std::span<const Image> estimates, std::span<const Image> masks);

// The pixels whose shading the shadow test decides — inside the shadow map, on surfaces facing
// the light beyond grazing — from a renderer lookup image (channel 3 == 1). Throws on an image
// that is not one (a frame rendered without RenderSettings::lookupInputs has none).
Image litSurfaceMask(const Image& lookup);

// The median of a non-empty set of timings or values (the mean of the middle two for an even
// count); throws Error when empty.
double median(std::vector<double> values);

// Visibility minus the reference where `coverage` (litSurfaceMask) holds, 0 elsewhere: the signed
// error the report's heat maps and the viewer's error view show (positive: leaks light).
Image signedVisibilityError(const Image& visibility, const Image& reference, const Image& coverage);

}  // namespace penumbra
