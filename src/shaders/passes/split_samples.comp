// Lloyd relaxation samples for layered VSM (thesis §4.1.2): per 2x2 texel block of the unwarped
// moments, the second-occluder depth mu + sigma and its weight sigma^2 (zero when flat), in the
// order and arithmetic of the CPU reference (src/core/layer_placement.cpp).
layout(local_size_x = 8, local_size_y = 8) in;
#if MSAA
layout(binding = 0) uniform sampler2DMS depthMap;
#else
layout(binding = 0) uniform sampler2D depthMap;
#endif
layout(std430, binding = 1) writeonly buffer Samples {
  vec2 samples[];
};
uniform ivec2 size;
uniform float minWeight;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x + 1 >= size.x || p.y + 1 >= size.y) return;
  float m1 = 0.0f;
  float m2 = 0.0f;
  bool empty = false;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      float z = texelFetch(depthMap, p + ivec2(i, j), 0).x;
      m1 += 0.25f * z;
      m2 += 0.25f * z * z;
      empty = empty || z >= 1.0f;  // the cleared far plane: an edge against nothing
    }
  }
  precise float variance = max(m2 - m1 * m1, 0.0f);
  float weight = variance > minWeight && !empty ? variance : 0.0f;
  samples[p.y * (size.x - 1) + p.x] = vec2(m1 + sqrt(variance), weight);
}
