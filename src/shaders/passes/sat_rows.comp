// Summed-area table, step 2: each channel's quantisation from its extremes (shared/summed_area.h,
// as the CPU table derives it), then each texel quantised with the power-of-two scale (an exact
// fp32 product, no division), less the centre's units, and prefix-summed along its row, wrapping
// by design.
#extension GL_ARB_gpu_shader_int64 : require
#include "../lib/summed_area.glsl"
#include "../shared/summed_area.h"

layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2DArray penumbraChannelMap;
layout(std430, binding = 1) readonly buffer Extremes {
  uint extremes[];  // per channel: key of the lowest value, complement of the highest's
};
layout(std430, binding = 2) writeonly buffer Stats {
  SatChannelStats stats[];  // what the lookups read
};
layout(std430, binding = 3) writeonly buffer Sums {
  uint64_t sums[];
};

uniform ivec2 size;
uniform int channelCount;  // every cascade's channels
uniform int channelsPerCascade;
uniform int layersPerCascade;

void main() {
  int y = int(gl_GlobalInvocationID.x);
  int channel = int(gl_GlobalInvocationID.y);
  if (y >= size.y || channel >= channelCount) return;
  SummedAreaQuantisation q = summedAreaQuantisationFor(satKeyValue(extremes[2 * channel]),
                                                       satKeyValue(~extremes[2 * channel + 1]));
  if (y == 0) {
    SatChannelStats s;
    s.centre = q.centre;
    s.step = q.step;
    stats[channel] = s;
  }
  int64_t offset = int64_t(q.offset);
  uint64_t running = 0UL;
  for (int x = 0; x < size.x; ++x) {
    float v =
        satChannelValue(penumbraChannelMap, channel, x, y, channelsPerCascade, layersPerCascade);
    running += uint64_t(int64_t(roundEven(summedAreaUnits(v, q))) - offset);
    sums[satIndex(channel, x, y, size)] = running;
  }
}
