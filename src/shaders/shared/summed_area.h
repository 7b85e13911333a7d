// Summed-area tables in wrapping 64-bit fixed point (penumbra/summed_area_table.h): each channel
// is centred on its mean and quantised with 2^31 steps per unit of its largest deviation R, so
// prefix sums wrap modulo 2^64 and box sums are exact. The GPU's table pass, the CPU table and the
// lookups share these.
#ifndef PENUMBRA_SHARED_SUMMED_AREA_H
#define PENUMBRA_SHARED_SUMMED_AREA_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// The value of one fixed-point unit for a channel whose values lie within `deviation` of its
// centre: R * 2^-31 (a constant channel keeps unit steps).
PENUMBRA_INLINE double summedAreaStepFor(double deviation) {
  return (deviation > double(0.0f) ? deviation : double(1.0f)) / double(2147483648.0f);
}

// A box's mean from its sum in fixed-point units (the wrapped difference of prefix sums, exact).
PENUMBRA_INLINE double summedAreaMean(double fixedSum, double area, double step, double centre) {
  return fixedSum * step / area + centre;
}

PENUMBRA_END_SHARED
#endif
