// The camera pass's shading: Lambert plus ambient, the shadow test scaling the direct part. The
// GPU shades with it, and the renderer when it fills in reference pixels on the CPU.
#ifndef PENUMBRA_SHARED_SHADING_H
#define PENUMBRA_SHARED_SHADING_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// The cosine between a surface's normal and the direction to the light below which the shadow
// test no longer decides the shading (the camera pass's lookup w = 0.5, litSurfaceMask): a
// grazing surface makes any receiver plane meaningless, and a surface facing away is dark
// whatever the test says. The ray-traced truth holds a triangle's own plane to the same cutoff.
const float kGrazingCosine = 0.05f;

// What the camera pass shows where no surface is drawn (its clear colour), linear RGB.
const vec3 kSkyColour = vec3(0.62f, 0.72f, 0.86f);

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
