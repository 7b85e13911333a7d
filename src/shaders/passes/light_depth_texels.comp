// Read-back of the depth PCF and the hard test filter, which have no channel texture: one
// cascade's light-pass depth texel by texel as their lookup reads it (lightDepthTexel: the nearest
// sample under MSAA), into a single-sampled R32F image GL can read back. For tests and the
// viewer's channel view: Renderer::readChannels.
#if SUMMED_AREA
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "../lib/lookup_access.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32f) uniform writeonly image2D target;
uniform int cascade;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = penumbraLookup.shadowMapSize;
  if (texel.x >= size || texel.y >= size) return;
  LookupSources sources;
  sources.cascade = cascade;
  imageStore(target, texel, vec4(lightDepthTexel(sources, texel)));
}
