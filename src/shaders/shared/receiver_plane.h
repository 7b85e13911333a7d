// The receiver plane's depth gradient over the light's plane (receiver-plane depth bias), solved
// once for the camera pass (steps along the rasterised triangle) and for a host's penumbraShadow()
// (screen derivatives of its shadow coordinates).
#ifndef PENUMBRA_SHARED_RECEIVER_PLANE_H
#define PENUMBRA_SHARED_RECEIVER_PLANE_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// a, b: two steps along the receiver, each a step on the light's plane (x, y) and the depth
// change along it (z). Solves g . (a.x, a.y) = a.z and g . (b.x, b.y) = b.z for the gradient g;
// 0 where the steps are (nearly) parallel on the light's plane: the surface is seen edge-on from
// the light and no plane lies over the texels. The test is relative to the steps' size, so it
// holds at any magnification.
PENUMBRA_INLINE vec2 solveDepthGradient(vec3 a, vec3 b) {
  float determinant = a.x * b.y - a.y * b.x;
  float scale = a.x * a.x + a.y * a.y + b.x * b.x + b.y * b.y;
  if (abs(determinant) <= 1e-6f * scale) return vec2(0.0f);
  return vec2(b.y * a.z - a.y * b.z, a.x * b.z - b.x * a.z) / determinant;
}

PENUMBRA_END_SHARED
#endif
