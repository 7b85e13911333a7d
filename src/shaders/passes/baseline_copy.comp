// `penumbra bench --passes`: the minimal kernel beside the encode pass — the same read of the
// light pass's depth and the same writes to every channel layer, with no technique math. Each
// channel gets its own value, as an encode's do: storing one value in all four lets the compiler
// convert it to the storage format once: on llvmpipe such a copy of CSM's eight RGBA8 layers took
// 41-46 ms where four distinct values per texel took 55-56 (passes-llvmpipe-2026-12-02.md in
// docs/results). The layer count is a compile-time constant (LAYER_COUNT), as the encode's.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray depth;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform ivec2 size;
const int kLayerCount = LAYER_COUNT;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  float z = texelFetch(depth, ivec3(p, 0), 0).x;
  const vec4 channelScale = vec4(1.0, 0.75, 0.5, 0.25);
  for (int layer = 0; layer < kLayerCount; ++layer) {
    imageStore(target, ivec3(p, layer), z * channelScale + float(layer) / 16.0);
  }
}
