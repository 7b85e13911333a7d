// Summed-area tables in wrapping 64-bit fixed point (penumbra/summed_area_table.h): each channel
// is centred on the midpoint of its range and quantised with a power-of-two step of at most
// R * 2^-31, R its largest deviation from that centre, so prefix sums wrap modulo 2^64 and box
// sums are exact. The GPU's table passes, the CPU table and the lookups share these.
#ifndef PENUMBRA_SHARED_SUMMED_AREA_H
#define PENUMBRA_SHARED_SUMMED_AREA_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct SummedAreaQuantisation {
  double centre;
  double step;   // value of one fixed-point unit: a power of two
  double scale;  // 1 / step, also a power of two, so quantising multiplies exactly
};

// The quantisation of a channel whose values lie in [lo, hi]. The centre is the range's midpoint
// (R = (hi - lo) / 2, the smallest largest deviation of any centre), and the step the power of
// two 2^(e-32) with 2^(e-1) <= R < 2^e: |fixed| <= R / step < 2^32, and half a step, the
// quantisation error, is at most R * 2^-32. Only the extremes enter, so a GPU reduction in any
// order reaches the same bits as the CPU. A constant channel (R = 0) quantises to 0 everywhere
// and its box means are its value exactly.
PENUMBRA_INLINE SummedAreaQuantisation summedAreaQuantisationFor(float lo, float hi) {
  SummedAreaQuantisation q;
  q.centre = (double(lo) + double(hi)) * double(0.5f);
  const double deviation = max(double(hi) - q.centre, q.centre - double(lo));
  int exponent = 0;
  frexp(deviation, exponent);  // deviation = m * 2^exponent, m in [0.5, 1); 0 gives exponent 0
  q.step = ldexp(double(1.0f), exponent - 32);
  q.scale = ldexp(double(1.0f), 32 - exponent);
  return q;
}

// A texel's value in fixed-point units before rounding: (value - centre) * scale, one rounding
// (the subtraction) then an exact power-of-two product. Each side rounds the result to the
// nearest integer, ties to even (GLSL roundEven, C++ std::nearbyint): both IEEE
// roundToIntegralTiesToEven, so GPU and CPU quantise identically.
PENUMBRA_INLINE double summedAreaScaled(float value, SummedAreaQuantisation q) {
  return (double(value) - q.centre) * q.scale;
}

// A box's mean from its sum in fixed-point units (the wrapped difference of prefix sums, exact).
PENUMBRA_INLINE double summedAreaMean(double fixedSum, double area, double step, double centre) {
  return fixedSum * step / area + centre;
}

PENUMBRA_END_SHARED
#endif
