// `penumbra bench --passes`: the minimal kernel beside the prefilter — one axis of a plain
// separable blur with the same taps, format and layers: weighted sums of whole texels.
#include "../shared/filter_weights.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray source;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform float weights[2 * kMaxBlurRadius + 1];
uniform int radius;
uniform ivec2 direction;
uniform ivec2 size;
uniform int layerCount;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  for (int layer = 0; layer < layerCount; ++layer) {
    vec4 sum = vec4(0.0f);
    for (int i = -radius; i <= radius; ++i) {
      ivec2 q = clamp(p + i * direction, ivec2(0), size - 1);
      sum += weights[i + radius] * texelFetch(source, ivec3(q, layer), 0);
    }
    imageStore(target, ivec3(p, layer), sum);
  }
}
