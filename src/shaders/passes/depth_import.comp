// A host's depth texture -> penumbra's linear depth (ShadowFilter): window depth of the host's
// light projection through windowDepthToLinear (orthographic: unchanged), or a host's R32F
// linear depth copied, into one R32F layer per map layer.
#include "../shared/lookup_block.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, r32f) uniform writeonly image2DArray linearImage;
#if ARRAY_INPUT
layout(binding = 0) uniform sampler2DArray hostDepth;
#else
layout(binding = 0) uniform sampler2D hostDepth;
#endif
uniform ivec2 size;
uniform int perspective;  // 1: the host's projection is perspective (hyperbolic window depth)
uniform float nearDistance;
uniform float farDistance;

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);  // z: the layer
  if (p.x >= size.x || p.y >= size.y) return;
#if ARRAY_INPUT
  float d = texelFetch(hostDepth, p, 0).x;
#else
  float d = texelFetch(hostDepth, p.xy, 0).x;
#endif
  float linear = windowDepthToLinear(d, perspective, nearDistance, farDistance);
  imageStore(linearImage, p, vec4(linear, 0.0f, 0.0f, 0.0f));
}
