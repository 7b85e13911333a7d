// Depth-only camera pass (the depth-bounds reduction's input): nothing to write but depth, and
// alpha-masked surfaces cut out as the camera pass cuts them, so their holes bound nothing.
#include "../lib/material.glsl"

in vec3 worldPosition;
in vec3 worldNormal;
in vec2 baseColorTexcoord;

void main() {
#if ALPHA_TEST
  if (!materialCovers(baseColorTexcoord)) discard;
#endif
}
