// A mesh's material as the light, depth-only and camera passes read it (GpuScene::Material, set
// by setMaterialUniforms): base colour = factor x sRGB texture (read linear), and the alpha mask
// of glTF 2.0 §3.9.4 (shared/alpha_mask.h); the camera sees a BLEND material as a mask at 0.5, the
// light pass lets 1 - alpha through it (materialCastsAt).
#include "../shared/alpha_mask.h"

// 1: the pass cuts out what the mask does not cover (a shader that may discard); 0: a variant for
// opaque meshes only, which keeps early depth testing (gl/material_programs.h).
#ifndef ALPHA_TEST
#define ALPHA_TEST 1
#endif

uniform vec3 albedo;            // base-colour factor, linear
uniform float baseColorAlpha;   // its alpha
uniform float alphaCutoff;      // < 0: opaque, no test
uniform int alphaBlend;         // 1: a translucent (BLEND) material
uniform int hasBaseColorTexture;
layout(binding = PENUMBRA_BASE_COLOR_TEXTURE_UNIT) uniform sampler2D baseColorTexture;

// Call in uniform control flow: the texture's mip level needs derivatives.
vec4 materialBaseColor(vec2 texcoord) {
  vec4 baseColor = vec4(albedo, baseColorAlpha);
  if (hasBaseColorTexture != 0) baseColor *= texture(baseColorTexture, texcoord);
  return baseColor;
}

bool materialCovers(vec2 texcoord) {
  return alphaCutoff < 0.0f || alphaCovers(materialBaseColor(texcoord).a, alphaCutoff);
}

// Whether the material blocks the light at this shadow-map texel: the mask, and for a
// translucent material the dither that lets through 1 - alpha (shared/alpha_mask.h).
bool materialCastsAt(vec2 texcoord, ivec2 texel) {
  if (alphaBlend == 0) return materialCovers(texcoord);
  return translucentCovers(materialBaseColor(texcoord).a, texel.x, texel.y);
}
