// `penumbra bench --passes`: the yardstick's copy (../shared/yardsticks/rawblur.c), its GLSL as
// that program compiles it: one texel fetch through a sampler, one image store.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D s;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2D o;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  imageStore(o, p, texelFetch(s, p, 0));
}
