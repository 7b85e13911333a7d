// Light pass: the linear depth metric in [0,1] (distance along the light direction for
// directional lights, Euclidean distance for spot lights, thesis §4.1.3), mapped from [near, far].
// Alpha-masked casters are tested against their base colour's alpha, so leaves cast the shadow
// of their shape, not of their cards; with MSAA the renderer runs masked draws per sample.
// Translucent (BLEND) casters cover a dithered 1 - alpha share of the texels.
#include "../lib/material.glsl"
#include "../shared/light_depth.h"

in vec3 lightViewPosition;
in vec2 baseColorTexcoord;

uniform int lightPerspective;
uniform float lightNear;
uniform float lightFar;

layout(location = 0) out float linearDepth;

void main() {
#if ALPHA_TEST
  if (!materialCastsAt(baseColorTexcoord, ivec2(gl_FragCoord.xy))) discard;
#endif
  linearDepth = clamp(
      lightLinearDepth(lightViewPosition, lightPerspective != 0, lightNear, lightFar), 0.0f, 1.0f);
}
