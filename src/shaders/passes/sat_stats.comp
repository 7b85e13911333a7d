// Summed-area table, step 1: per (row, channel) the sum, min and max of the level-0 channels.
#extension GL_ARB_gpu_shader_int64 : require
#include "../lib/summed_area.glsl"

layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2DArray channelMap;

struct RowStats {
  double sum;
  float lo;
  float hi;
};
layout(std430, binding = 1) writeonly buffer Rows {
  RowStats rows[];
};

uniform ivec2 size;
uniform int channelCount;  // every cascade's channels
uniform int channelsPerCascade;
uniform int layersPerCascade;

void main() {
  int y = int(gl_GlobalInvocationID.x);
  int channel = int(gl_GlobalInvocationID.y);
  if (y >= size.y || channel >= channelCount) return;
  double sum = 0.0LF;
  float lo = 3.4e38f;
  float hi = -3.4e38f;
  for (int x = 0; x < size.x; ++x) {
    float v = satChannelValue(channelMap, channel, x, y, channelsPerCascade, layersPerCascade);
    sum += double(v);
    lo = min(lo, v);
    hi = max(hi, v);
  }
  RowStats r;
  r.sum = sum;
  r.lo = lo;
  r.hi = hi;
  rows[channel * size.y + y] = r;
}
