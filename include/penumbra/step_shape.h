// Measures of how a technique's curve reproduces the shadow test's step (CSM paper Fig. 3, ESM
// paper Fig. 2): where it crosses 1/2, how wide its transition is, how far it rings beyond the
// transition, and its error integrated against the exact step.
#pragma once

#include <vector>

namespace penumbra {

// A curve of visibility v(x) over x = d - z (receiver minus occluder depth, increasing), for
// one occluder covering the whole filter region: the exact test is 1 for x <= 0, 0 beyond.
struct StepCurve {
  std::vector<float> x;  // increasing
  std::vector<float> v;  // visibility at each x
};

struct StepShape {
  float halfCrossing = 0.0f;     // x where v first falls through 1/2 (linearly interpolated)
  float lit90 = 0.0f;            // the last x before halfCrossing with v >= 0.9
  float shadow10 = 0.0f;         // the first x after halfCrossing with v <= 0.1
  float transitionWidth = 0.0f;  // shadow10 - lit90: the 90 % to 10 % fall
  // Ringing: how far the curve turns back, the largest rise after falling beyond halfCrossing or
  // fall after rising before it (0 for a monotone step). Of the visibility as given: where it is
  // clamped to [0,1], Gibbs' overshoot past 1 or 0 is hidden and the next ripple is what shows.
  float ringing = 0.0f;
  // The first trough of the ringing on the lit side: the distance from halfCrossing back to the
  // first local minimum of v below 1 - 1e-3 (a truncated Fourier series' ripples repeat every
  // 1/M; CSM eq. 10); 0 when the curve has none.
  float firstTroughDistance = 0.0f;
};

// Throws Error when the curve has fewer than 3 samples, x is not increasing, the sizes differ or
// v never falls through 1/2.
StepShape measureStepShape(const StepCurve& curve);

// The integral of |v - H(-x)| over [from, to] (trapezoids between samples; the exact step is 1
// for x <= 0, 0 beyond), e.g. the area between a curve and the exact test.
double stepErrorArea(const StepCurve& curve, float from, float to);

// max |v - H(-x)| over samples with x in [from, to]; 0 when none lies there.
float stepErrorMax(const StepCurve& curve, float from, float to);

}  // namespace penumbra
