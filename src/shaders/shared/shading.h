// The camera pass's shading: Lambert plus ambient, the shadow test scaling the direct part. The
// GPU shades with it, and the renderer when it fills in reference pixels on the CPU.
#ifndef PENUMBRA_SHARED_SHADING_H
#define PENUMBRA_SHARED_SHADING_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// lightAmount: N.L times the spot cone's falloff, in [0,1]; ambient: the ambient share, [0,1].
PENUMBRA_INLINE vec3 shadeLambert(vec3 albedo, float ambient, float lightAmount, float visibility) {
  return albedo * (ambient + (1.0f - ambient) * lightAmount * visibility);
}

// A spot light's cone edge: full light inside the cone, none outside, a smooth step over 0.05 of
// cosine just inside it. cosineToAxis: of the angle between the spot's axis and the direction
// from the light to the surface; coneCosine: cos(half the cone angle).
PENUMBRA_INLINE float spotConeFalloff(float cosineToAxis, float coneCosine) {
  return smoothstep(coneCosine, coneCosine + 0.05f, cosineToAxis);
}

PENUMBRA_END_SHARED
#endif
