// Summed-area table, step 1: each channel's lowest and highest value, all its quantisation needs
// (shared/summed_area.h). One invocation per column and channel layer walks the column with
// whole-texel fetches (the 64 invocations of a group read four rows' segments at each step) and
// leaves its extremes with one atomicMin per channel and end: the result does not depend on the
// order, so it is the CPU's exactly.
#include "../lib/summed_area.glsl"

layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2DArray penumbraChannelMap;
layout(std430, binding = 1) buffer Extremes {
  uint extremes[];  // per channel: key of the lowest value, complement of the highest's
};

uniform ivec2 size;
uniform int channelsPerCascade;
uniform int layersPerCascade;

void main() {
  int x = int(gl_GlobalInvocationID.x);
  int layer = int(gl_GlobalInvocationID.z);  // cascade * layersPerCascade + layer in cascade
  if (x >= size.x) return;
  vec4 lo = vec4(uintBitsToFloat(0x7f800000u));  // +infinity
  vec4 hi = -lo;
  // Four rows an iteration, then the rows left over: on llvmpipe each iteration of a loop
  // bounded by a uniform pays for its mask bookkeeping; MSM's 1024^2 table took 1.07-1.14x its
  // plain prefix sums this way against 1.20-1.21x a row at a time
  // (docs/results/passes-llvmpipe-2026-12-06-box.md).
  int y = 0;
  for (; y + 4 <= size.y; y += 4) {
    vec4 a = texelFetch(penumbraChannelMap, ivec3(x, y, layer), 0);
    vec4 b = texelFetch(penumbraChannelMap, ivec3(x, y + 1, layer), 0);
    vec4 c = texelFetch(penumbraChannelMap, ivec3(x, y + 2, layer), 0);
    vec4 d = texelFetch(penumbraChannelMap, ivec3(x, y + 3, layer), 0);
    lo = min(lo, min(min(a, b), min(c, d)));
    hi = max(hi, max(max(a, b), max(c, d)));
  }
  for (; y < size.y; ++y) {
    vec4 v = texelFetch(penumbraChannelMap, ivec3(x, y, layer), 0);
    lo = min(lo, v);
    hi = max(hi, v);
  }
  int cascade = layer / layersPerCascade;
  int first = (layer % layersPerCascade) * 4;
  int count = min(4, channelsPerCascade - first);
  for (int k = 0; k < count; ++k) {
    int channel = cascade * channelsPerCascade + first + k;
    atomicMin(extremes[2 * channel], satOrderedKey(lo[k]));
    atomicMin(extremes[2 * channel + 1], ~satOrderedKey(hi[k]));
  }
}
