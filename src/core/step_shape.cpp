// Step-shape measures of a shadow-test curve (penumbra/step_shape.h).
#include "penumbra/step_shape.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "penumbra/error.h"

namespace penumbra {
namespace {

float exactStep(float x) {
  return x <= 0.0f ? 1.0f : 0.0f;
}

void checkCurve(const StepCurve& c) {
  if (c.x.size() != c.v.size()) throw Error("step curve: x and v differ in size");
  if (c.x.size() < 3) throw Error("step curve: fewer than 3 samples");
  for (size_t i = 1; i < c.x.size(); ++i) {
    if (!(c.x[i] > c.x[i - 1])) {
      throw Error("step curve: x not increasing at sample " + std::to_string(i));
    }
  }
}

}  // namespace

StepShape measureStepShape(const StepCurve& c) {
  checkCurve(c);
  const size_t n = c.x.size();
  size_t fall = n;  // first i with v[i-1] >= 1/2 > v[i]
  for (size_t i = 1; i < n && fall == n; ++i) {
    if (c.v[i - 1] >= 0.5f && c.v[i] < 0.5f) fall = i;
  }
  if (fall == n) throw Error("step curve: visibility never falls through 1/2");
  StepShape s;
  const float t = (c.v[fall - 1] - 0.5f) / (c.v[fall - 1] - c.v[fall]);
  s.halfCrossing = c.x[fall - 1] + t * (c.x[fall] - c.x[fall - 1]);
  size_t lit = fall - 1;
  while (lit > 0 && c.v[lit] < 0.9f) --lit;
  size_t shadow = fall;
  while (shadow + 1 < n && c.v[shadow] > 0.1f) ++shadow;
  if (c.v[lit] < 0.9f) throw Error("step curve: visibility never reaches 0.9 before 1/2");
  if (c.v[shadow] > 0.1f) throw Error("step curve: visibility never falls to 0.1 after 1/2");
  s.lit90 = c.x[lit];
  s.shadow10 = c.x[shadow];
  s.transitionWidth = s.shadow10 - s.lit90;
  // Ringing is the curve turning back: beyond the crossing, how far it climbs above its lowest
  // value so far; before it, how far it dips below its highest value nearer the crossing.
  float lowest = c.v[fall];
  for (size_t i = fall; i < n; ++i) {
    lowest = std::min(lowest, c.v[i]);
    s.ringing = std::max(s.ringing, c.v[i] - lowest);
  }
  float highest = c.v[fall - 1];
  for (size_t i = fall; i-- > 0;) {
    highest = std::max(highest, c.v[i]);
    s.ringing = std::max(s.ringing, highest - c.v[i]);
  }
  for (size_t i = lit; i >= 1 && i + 1 < n; --i) {
    if (c.v[i] < 1.0f - 1e-3f && c.v[i] <= c.v[i - 1] && c.v[i] <= c.v[i + 1]) {
      s.firstTroughDistance = s.halfCrossing - c.x[i];
      break;
    }
  }
  return s;
}

double stepErrorArea(const StepCurve& c, float from, float to) {
  checkCurve(c);
  double area = 0.0;
  for (size_t i = 1; i < c.x.size(); ++i) {
    const float a = std::max(c.x[i - 1], from), b = std::min(c.x[i], to);
    if (!(b > a)) continue;
    auto value = [&](float x) {
      const float u = (x - c.x[i - 1]) / (c.x[i] - c.x[i - 1]);
      return c.v[i - 1] + u * (c.v[i] - c.v[i - 1]);
    };
    // The exact step jumps at x = 0: an interval holding it is two trapezoids, |v - 1| up to 0
    // and |v| after.
    if (a < 0.0f && b > 0.0f) {
      area += 0.5 * double(-a) * (std::abs(value(a) - 1.0f) + std::abs(value(0.0f) - 1.0f));
      area += 0.5 * double(b) * (std::abs(value(0.0f)) + std::abs(value(b)));
    } else {  // one side of the jump: the step is constant over [a, b], 0 if a is the jump
      const float step = b <= 0.0f ? 1.0f : 0.0f;
      area += 0.5 * double(b - a) * (std::abs(value(a) - step) + std::abs(value(b) - step));
    }
  }
  return area;
}

float stepErrorMax(const StepCurve& c, float from, float to) {
  checkCurve(c);
  float worst = 0.0f;
  for (size_t i = 0; i < c.x.size(); ++i) {
    if (c.x[i] >= from && c.x[i] <= to)
      worst = std::max(worst, std::abs(c.v[i] - exactStep(c.x[i])));
  }
  return worst;
}

}  // namespace penumbra
