// `penumbra bench --passes`: the minimal kernel beside the fused prefilter
// (passes/prefilter_fused.comp) — the same traffic in the same shape: one work group per TILE^2
// texels and channel layer loads its tile and a radius-wide border of depth once into shared
// memory, blurs the rows, then the columns, and writes each texel once. No technique math: the
// depth goes in as baseline_copy.comp's values, the radius and weights are compile-time constants
// (RADIUS, WEIGHTS) and the shared arrays hold the format's components only
// (lib/texel_components.glsl).
#include "../lib/texel_components.glsl"

layout(local_size_x = TILE, local_size_y = TILE) in;
layout(binding = 0) uniform sampler2DArray depth;
layout(binding = 0, CHANNEL_FORMAT) uniform writeonly image2DArray target;

uniform ivec2 size;
const int kRadius = RADIUS;
const float kWeights[2 * kRadius + 1] = WEIGHTS;
const int kSpan = TILE + 2 * kRadius;

shared Texel loaded[kSpan * kSpan];
shared Texel rows[kSpan * TILE];

void main() {
  int layer = int(gl_WorkGroupID.z);
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * TILE - kRadius;
  int local = int(gl_LocalInvocationIndex);
  const vec4 channelScale = vec4(1.0, 0.75, 0.5, 0.25);
  for (int i = local; i < kSpan * kSpan; i += TILE * TILE) {
    ivec2 q = clamp(origin + ivec2(i % kSpan, i / kSpan), ivec2(0), size - 1);
    float z = texelFetch(depth, ivec3(q, 0), 0).x;
    loaded[i] = (z * channelScale + float(layer) / 16.0).TEXEL_SWIZZLE;
  }
  barrier();
  for (int i = local; i < kSpan * TILE; i += TILE * TILE) {
    int first = (i / TILE) * kSpan + i % TILE;
    Texel sum = Texel(0.0f);
    for (int t = 0; t <= 2 * kRadius; ++t) sum += kWeights[t] * loaded[first + t];
    rows[i] = sum;
  }
  barrier();
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  int first = int(gl_LocalInvocationID.y) * TILE + int(gl_LocalInvocationID.x);
  Texel sum = Texel(0.0f);
  for (int t = 0; t <= 2 * kRadius; ++t) sum += kWeights[t] * rows[first + t * TILE];
  imageStore(target, ivec3(p, layer), widenTexel(sum));
}
