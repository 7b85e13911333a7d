// Summed-area tables in wrapping 64-bit fixed point (include/penumbra/summed_area_table.h): each
// channel is centred on its mean and quantised with 2^31 steps per unit of its largest deviation;
// prefix sums wrap modulo 2^64, leaving box sums exact. Sums are indexed (channel, y, x).
#ifndef PENUMBRA_LIB_SUMMED_AREA_GLSL
#define PENUMBRA_LIB_SUMMED_AREA_GLSL

struct SatChannelStats {
  double centre;
  double step;  // value of one fixed-point unit
};

// Table channel c is channel c % perCascade of cascade c / perCascade in the channel texture.
float satChannelValue(sampler2DArray channelMap, int channel, int x, int y, int perCascade,
                      int layersPerCascade) {
  int cascade = channel / perCascade;
  int k = channel % perCascade;
  return texelFetch(channelMap, ivec3(x, y, cascade * layersPerCascade + k / 4), 0)[k % 4];
}

uint satIndex(int channel, int x, int y, ivec2 size) {
  return (uint(channel) * uint(size.y) + uint(y)) * uint(size.x) + uint(x);
}

#endif
