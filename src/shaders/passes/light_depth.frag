// Light pass: the linear depth metric in [0,1] (distance along the light direction for
// directional lights, Euclidean distance for spot lights, thesis §4.1.3), mapped from [near, far].
// Alpha-masked casters are tested against their base colour's alpha, so leaves cast the shadow
// of their shape, not of their cards; with MSAA the renderer runs masked draws per sample.
#include "../shared/alpha_mask.h"

in vec3 lightViewPosition;
in vec2 baseColorTexcoord;

uniform int lightPerspective;
uniform float lightNear;
uniform float lightFar;
uniform float baseColorAlpha;  // the material's factor alpha
uniform float alphaCutoff;     // < 0: opaque, no test
uniform int hasBaseColorTexture;
layout(binding = PENUMBRA_BASE_COLOR_TEXTURE_UNIT) uniform sampler2D baseColorTexture;

layout(location = 0) out float linearDepth;

void main() {
  if (alphaCutoff >= 0.0f) {
    float alpha = baseColorAlpha;
    if (hasBaseColorTexture != 0) alpha *= texture(baseColorTexture, baseColorTexcoord).a;
    if (!alphaCovers(alpha, alphaCutoff)) discard;
  }
  float distance = lightPerspective != 0 ? length(lightViewPosition) : -lightViewPosition.z;
  linearDepth = clamp((distance - lightNear) / (lightFar - lightNear), 0.0f, 1.0f);
}
