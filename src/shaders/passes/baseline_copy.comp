// `penumbra bench --passes`: the minimal kernel beside the encode pass — the same read of the
// light pass's depth and the same writes to every channel layer, with no technique math. Each
// channel gets its own value, as an encode's do: storing one value in all four lets the compiler
// convert it to the storage format once: on llvmpipe such a copy of CSM's eight RGBA8 layers took
// 41-46 ms where four distinct values per texel took 55-56 (passes-llvmpipe-2026-12-02.md in
// docs/results). The layer count is a compile-time constant (LAYER_COUNT), as the encode's, and
// each invocation copies the encode's rows (ROWS_PER_INVOCATION).
layout(local_size_x = 8, local_size_y = 8) in;
// After the group's size, which it reads.
#include "../lib/column_rows.glsl"
layout(binding = 0) uniform sampler2DArray depth;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform ivec2 size;
const int kLayerCount = LAYER_COUNT;

void main() {
  int x = int(gl_GlobalInvocationID.x);
  if (x >= size.x || invocationRow(0) >= size.y) return;
  const vec4 channelScale = vec4(1.0, 0.75, 0.5, 0.25);
  float z[kRows];
  for (int k = 0; k < kRows; ++k) {
    z[k] = texelFetch(depth, ivec3(x, invocationFetchRow(k, size.y), 0), 0).x;
  }
  // Stores past the edge have no effect (GL 4.5 §8.26), as the encode's.
  for (int layer = 0; layer < kLayerCount; ++layer) {
    for (int k = 0; k < kRows; ++k) {
      imageStore(target, ivec3(x, invocationRow(k), layer),
                 z[k] * channelScale + float(layer) / 16.0);
    }
  }
}
