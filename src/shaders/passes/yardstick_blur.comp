// `penumbra bench --passes`: the yardstick's blur (../shared/yardsticks/rawblur.c, an independent
// check on the minimal kernels), its GLSL as that program compiles it: one axis of a box blur of
// a 2D texture through a sampler, radius compile-time (RADIUS), one 8x8 work group.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D s;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2D o;
uniform ivec2 dir;
const int R = RADIUS;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 m = textureSize(s, 0) - 1;
  vec4 a = vec4(0);
  for (int i = -R; i <= R; i++) {
    a += texelFetch(s, clamp(p + i * dir, ivec2(0), m), 0) * (1.0 / float(2 * R + 1));
  }
  imageStore(o, p, a);
}
