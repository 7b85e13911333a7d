// Summed-area tables in wrapping 64-bit fixed point (penumbra/summed_area_table.h): each channel
// is quantised to a grid of power-of-two steps of at most R * 2^-31, R its largest deviation from
// the midpoint of its range, and centred on the grid point at or below that midpoint, so prefix
// sums wrap modulo 2^64 and box sums are exact. The GPU's table passes, the CPU table and the
// lookups share these.
#ifndef PENUMBRA_SHARED_SUMMED_AREA_H
#define PENUMBRA_SHARED_SUMMED_AREA_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct SummedAreaQuantisation {
  double centre;  // offset * step: a value of the grid
  double step;    // value of one fixed-point unit: a power of two
  double scale;   // 1 / step, a power of two within fp32's normal range
  double offset;  // the centre in units: an integer
};

// The quantisation of a channel whose values lie in [lo, hi]. R = (hi - lo) / 2 is the smallest
// largest deviation of any centre, and the step the power of two 2^(e-32) with
// 2^(e-1) <= R < 2^e. The centre is the grid point at or below the range's midpoint, so
// |fixed| < R / step + 1.5, at most 2^32 + 1, and a value's fixed point is its own product with
// the scale rounded, less the centre's: per texel one fp32 product, exact (a power of two), where
// centring each value first took a double subtraction (1.3 ms of VSM's 1024^2 table on
// llvmpipe). The quantisation error stays half a step, at most R * 2^-32. A constant channel
// (R = 0) takes its magnitude's step, so its units stay within 2^32 and its box means are its
// value exactly (for |value| >= 2^-104). An R under 2^-95 takes the step 2^-127 (the scale
// 2^127, fp32's largest power of two), coarser than R * 2^-31 there but of no consequence at
// values under 2^-70 (a range of distinct fp32 values spans at least 2^-24 of their magnitude).
// Only the extremes enter, so a GPU reduction in any order reaches the same bits as the CPU
// (fp32 denormals aside, which a GPU may flush: values under 2^-126, in ranges under 2^-93).
PENUMBRA_INLINE SummedAreaQuantisation summedAreaQuantisationFor(float lo, float hi) {
  SummedAreaQuantisation q;
  const double midpoint = (double(lo) + double(hi)) * double(0.5f);
  const double deviation = max(double(hi) - midpoint, midpoint - double(lo));
  const double magnitude = max(abs(double(lo)), abs(double(hi)));
  int exponent = 0;
  // deviation = m * 2^exponent, m in [0.5, 1); 0 gives exponent 0
  frexp(deviation > double(0.0f) ? deviation : magnitude, exponent);
  const int shift = min(32 - exponent, 127);
  q.step = ldexp(double(1.0f), -shift);
  q.scale = ldexp(double(1.0f), shift);
  q.offset = floor(midpoint * q.scale);  // the product exact, a power of two
  q.centre = q.offset * q.step;
  return q;
}

// A texel's value in fixed-point units before rounding and centring: value * scale, exact in fp32
// (|value| * scale <= 2^56). Each side rounds it to the nearest integer, ties to even (GLSL
// roundEven, C++ std::nearbyint: both IEEE roundToIntegralTiesToEven), and subtracts the offset
// in 64-bit integers, so GPU and CPU quantise identically.
PENUMBRA_INLINE float summedAreaUnits(float value, SummedAreaQuantisation q) {
  return value * float(q.scale);
}

// A box's mean from its sum in fixed-point units (the wrapped difference of prefix sums, exact).
PENUMBRA_INLINE double summedAreaMean(double fixedSum, double area, double step, double centre) {
  return fixedSum * step / area + centre;
}

// The GPU table's 64-bit sums are indexed (channel, y, x), each row padded by one 64-byte line
// (kSummedAreaRowPadding sums): the rows pass gives each invocation a row, so a CPU rasteriser's
// SIMD lanes (llvmpipe's eight) store to adjacent rows at once, and at power-of-two sizes rows
// a power of two of bytes apart share one cache set. Unpadded, VSM's table on llvmpipe was
// bimodal by process (docs/results/passes-llvmpipe-2026-12-06-rows.md).
const int kSummedAreaRowPadding = 8;
PENUMBRA_INLINE int summedAreaRowPitch(int width) {
  return width + kSummedAreaRowPadding;
}
// The index of channel `channel`'s sum at (x, y) in a width x height table. Its entries stay
// below 2^32 (ShadowFilter refuses larger tables), so 32 bits hold it.
PENUMBRA_INLINE uint summedAreaIndex(int channel, int x, int y, int width, int height) {
  return (uint(channel) * uint(height) + uint(y)) * uint(summedAreaRowPitch(width)) + uint(x);
}

PENUMBRA_END_SHARED
#endif
