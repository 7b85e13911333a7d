// The nearest and farthest view depth of drawn pixels (sample-distribution shadow maps,
// Lauritzen et al. 2011): each invocation converts its pixel's window depth back to view depth
// and folds it into two atomics; positive floats order like their bit patterns.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D depthMap;
layout(std430, binding = 1) buffer Bounds {
  uint nearestBits;
  uint farthestBits;
};
uniform ivec2 size;
uniform float near;  // the camera projection's planes
uniform float far;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= size.x || p.y >= size.y) return;
  float window = texelFetch(depthMap, p, 0).x;
  if (window >= 1.0f) return;  // background
  float ndc = 2.0f * window - 1.0f;
  float viewDepth = 2.0f * near * far / (far + near - ndc * (far - near));
  uint bits = floatBitsToUint(max(viewDepth, near));
  atomicMin(nearestBits, bits);
  atomicMax(farthestBits, bits);
}
