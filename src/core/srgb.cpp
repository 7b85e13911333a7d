// The sRGB encoding of IEC 61966-2-1:1999: a linear segment near black, a 1/2.4 power above;
// the standard's 0.0031308 threshold is where the two meet (both give 0.04045 there).
#include "penumbra/srgb.h"

#include <cmath>

namespace penumbra {

float srgbFromLinear(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // and NaN
  if (linear >= 1.0f) return 1.0f;
  if (linear <= 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float linearFromSrgb(float encoded) {
  if (!(encoded > 0.0f)) return 0.0f;  // and NaN
  if (encoded >= 1.0f) return 1.0f;
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace penumbra
