// Z-max pyramid, level 0: the light pass's depth (the farthest sample under MSAA) for ESM's Z-max
// failure classification (ESM paper §3.3); passes/mip_reduce.frag with FORCE_REDUCTION max builds
// the levels above it.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32f) uniform writeonly image2DArray zmaxImage;
#if MSAA
layout(binding = 0) uniform sampler2DMSArray depthMap;
uniform int sampleCount;
#else
layout(binding = 0) uniform sampler2DArray depthMap;
#endif
uniform ivec2 size;

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);  // z: the cascade
  if (p.x >= size.x || p.y >= size.y) return;
#if MSAA
  float z = 0.0f;
  for (int s = 0; s < sampleCount; ++s) z = max(z, texelFetch(depthMap, p, s).x);
#else
  float z = texelFetch(depthMap, p, 0).x;
#endif
  imageStore(zmaxImage, p, vec4(z, 0.0f, 0.0f, 0.0f));
}
