// Where a shadow ray starts: the hit point moved off its own triangle by a distance that scales
// with the point's floating-point precision, not by a world-space bias. Wächter and Binder, "A
// Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), chapter 6:
// each coordinate steps kIntScale * n units in the last place along the geometric normal n, so
// the move is always a few hundred ulps — more than the hit point's own rounding (a few ulps
// from the barycentric interpolation) and far less than any geometry's feature size — and
// coordinates near zero, where ulps vanish, move by kFloatScale * n instead.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace penumbra::truth {

// The chapter's constants: below kOrigin a coordinate's ulp is under 2^-28, so the fixed step
// kFloatScale (2^-16) is the larger one.
inline constexpr float kOffsetOrigin = 1.0f / 32.0f;
inline constexpr float kOffsetFloatScale = 1.0f / 65536.0f;
inline constexpr float kOffsetIntScale = 256.0f;

// p: the hit point (interpolated from the triangle's vertices); n: the triangle's unit
// geometric normal on the side the ray leaves from.
inline glm::vec3 offsetRayOrigin(glm::vec3 p, glm::vec3 n) {
  glm::vec3 moved;
  for (int i = 0; i < 3; ++i) {
    const int32_t step = int32_t(kOffsetIntScale * n[i]);
    // Sign-magnitude floats: adding to the bits of a negative number moves it away from zero.
    const int32_t bits = std::bit_cast<int32_t>(p[i]) + (p[i] < 0.0f ? -step : step);
    moved[i] = std::abs(p[i]) < kOffsetOrigin ? p[i] + kOffsetFloatScale * n[i]
                                              : std::bit_cast<float>(bits);
  }
  return moved;
}

}  // namespace penumbra::truth
