// The light's linear depth metric (thesis §4.1.3): distance along the light's direction for a
// directional light, Euclidean distance from a spot or point light, mapped from [near, far] to
// [0, 1]. The light pass writes it, the camera pass compares receivers in it, the figures place
// a scene's surfaces in it.
#ifndef PENUMBRA_SHARED_LIGHT_DEPTH_H
#define PENUMBRA_SHARED_LIGHT_DEPTH_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// `lightView`: the point in the light's view space (the light at the origin looking down -z) or,
// for a point light, the point minus the light's position.
PENUMBRA_INLINE float lightLinearDepth(vec3 lightView, bool perspective, float nearDistance,
                                       float farDistance) {
  float distance = perspective ? length(lightView) : -lightView.z;
  return (distance - nearDistance) / (farDistance - nearDistance);
}

// The distance (or distance along the direction) back from a linear depth.
PENUMBRA_INLINE float lightDistanceAtDepth(float depth, float nearDistance, float farDistance) {
  return nearDistance + depth * (farDistance - nearDistance);
}

PENUMBRA_END_SHARED
#endif
