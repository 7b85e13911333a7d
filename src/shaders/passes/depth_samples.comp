// Read-back of a multisampled light-pass layer: sample s of every texel into layer s of a
// single-sampled R32F array, which GL can read back (glGetTextureSubImage refuses multisampled
// textures). For tests and diagnostics: Renderer::readDepthSamples.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DMSArray depthSamples;
layout(binding = 0, r32f) uniform writeonly image2DArray target;
uniform ivec2 size;
uniform int layer;
uniform int sampleCount;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  for (int s = 0; s < sampleCount; ++s) {
    imageStore(target, ivec3(p, s), vec4(texelFetch(depthSamples, ivec3(p, layer), s).x));
  }
}
