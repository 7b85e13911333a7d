// `penumbra bench --passes`: the minimal kernel beside the prefilter — one axis of a plain
// separable blur of one layer with the same taps and format: weighted sums of whole texels, the
// radius and weights compile-time constants (RADIUS, WEIGHTS), the layer bound as a 2D image.
// The plainest blur the device runs for this traffic: on llvmpipe image loads cost a third of
// texel fetches through a sampler, and the loop has a constant trip count
// (docs/results/passes-llvmpipe-2026-12-04.md; the yardstick ../shared/yardsticks/rawblur.c,
// which fetches through a sampler, runs beside it in the bench).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1, CHANNEL_FORMAT) uniform readonly image2D source;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2D target;

const int kRadius = RADIUS;
const float kWeights[2 * kRadius + 1] = WEIGHTS;
uniform ivec2 direction;
uniform ivec2 size;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  vec4 sum = vec4(0.0f);
  for (int i = -kRadius; i <= kRadius; ++i) {
    sum += kWeights[i + kRadius] * imageLoad(source, clamp(p + i * direction, ivec2(0), size - 1));
  }
  imageStore(target, p, sum);
}
