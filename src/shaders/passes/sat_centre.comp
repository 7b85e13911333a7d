// Summed-area table, step 2: per channel the centre (mean) and the fixed-point step R / 2^31,
// R the largest deviation from the centre.
#extension GL_ARB_gpu_shader_int64 : require
#include "../lib/summed_area.glsl"
#include "../shared/summed_area.h"

layout(local_size_x = 1) in;

struct RowStats {
  double sum;
  float lo;
  float hi;
};
layout(std430, binding = 1) readonly buffer Rows {
  RowStats rows[];
};
layout(std430, binding = 2) writeonly buffer Stats {
  SatChannelStats stats[];
};

uniform ivec2 size;

void main() {
  int channel = int(gl_GlobalInvocationID.x);
  double sum = 0.0LF;
  float lo = 3.4e38f;
  float hi = -3.4e38f;
  for (int y = 0; y < size.y; ++y) {
    RowStats r = rows[channel * size.y + y];
    sum += r.sum;
    lo = min(lo, r.lo);
    hi = max(hi, r.hi);
  }
  double centre = sum / (double(size.x) * double(size.y));
  double deviation = max(double(hi) - centre, centre - double(lo));
  SatChannelStats s;
  s.centre = centre;
  s.step = summedAreaStepFor(deviation);
  stats[channel] = s;
}
