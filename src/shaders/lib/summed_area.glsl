// Summed-area tables in wrapping 64-bit fixed point (include/penumbra/summed_area_table.h): each
// channel is quantised with a power-of-two step of at most R * 2^-31 and centred on the step's
// grid at or below the midpoint of its range (shared/summed_area.h); prefix sums wrap modulo
// 2^64, leaving box sums exact.
// Sums are indexed (channel, y, x), rows padded (summedAreaRowPitch).
#ifndef PENUMBRA_LIB_SUMMED_AREA_GLSL
#define PENUMBRA_LIB_SUMMED_AREA_GLSL
#include "../shared/summed_area.h"

struct SatChannelStats {
  double centre;
  double step;  // value of one fixed-point unit
};

// Table channel c is channel c % perCascade of cascade c / perCascade in the channel texture.
float satChannelValue(sampler2DArray penumbraChannelMap, int channel, int x, int y, int perCascade,
                      int layersPerCascade) {
  int cascade = channel / perCascade;
  int k = channel % perCascade;
  return texelFetch(penumbraChannelMap, ivec3(x, y, cascade * layersPerCascade + k / 4), 0)[k % 4];
}

uint satIndex(int channel, int x, int y, ivec2 size) {
  return summedAreaIndex(channel, x, y, size.x, size.y);
}

// The channels' extremes as order-preserving keys (unsigned order = float order, -0 below +0),
// so atomicMin finds them. Each channel holds two keys, both reduced with atomicMin: the lowest
// value's key, then the complement of the highest's; a buffer cleared to all ones starts empty.
uint satOrderedKey(float v) {
  uint bits = floatBitsToUint(v);
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

float satKeyValue(uint key) {
  return uintBitsToFloat((key & 0x80000000u) != 0u ? key & 0x7fffffffu : ~key);
}

#endif
