// Camera pass: receiver depth in light space (with normal offset), the technique's visibility,
// and Lambert + ambient shading of the base colour (factor x sRGB texture). Writes colour and the
// float visibility. Alpha-masked surfaces are cut out by the same test as in the light pass.
#if SUMMED_AREA
#extension GL_ARB_gpu_shader_int64 : require
#endif
#ifndef ZMAX
#define ZMAX 0
#endif
#ifndef REFERENCE
#define REFERENCE 0
#endif
#ifndef MSAA
#define MSAA 0
#endif
#include "../lib/lookup_access.glsl"
#include "../shared/alpha_mask.h"
#include "../shared/shading.h"

in vec3 worldPosition;
in vec3 worldNormal;
in vec2 baseColorTexcoord;

uniform mat4 lightViewFromWorld;
uniform mat4 lightClipFromView;
uniform int lightPerspective;
uniform float lightNear;
uniform float lightFar;
uniform vec3 lightDirection;  // directional: the way light travels
uniform vec3 lightPosition;   // spot
uniform vec3 spotAxis;        // spot: unit direction from the light to its target
uniform float spotCosine;     // spot: cos(half cone angle)
uniform float normalOffset;   // world units per unit light distance (spot) or absolute
uniform float texelWorldSize;  // one shadow-map texel in world units (per unit distance, spot)
uniform vec3 albedo;            // base-colour factor, linear
uniform float baseColorAlpha;   // its alpha
uniform float alphaCutoff;      // < 0: opaque, no test
uniform int hasBaseColorTexture;
layout(binding = PENUMBRA_BASE_COLOR_TEXTURE_UNIT) uniform sampler2D baseColorTexture;
uniform float ambient;

layout(location = 0) out vec4 color;
layout(location = 1) out float visibilityOut;
layout(location = 2) out float diagnosticOut;  // ShadowSample's; -1 where nothing is drawn
layout(location = 3) out vec4 lookupOut;       // shadow-map uv, receiver depth, where (see main)
layout(location = 4) out vec2 depthPerTexelOut;  // the receiver plane's depth gradient per texel
layout(location = 5) out vec4 uvDerivativesOut;  // dFdx(uv), dFdy(uv): the lookup's footprint

const float kGrazingCosine = 0.05f;
// Below llvmpipe's 65535 loop iterations per invocation, with room for the loops' own rows.
const float kMaxReferenceTestsPerPixel = 48000.0f;

float linearDepth(vec3 lightView) {
  float distance = lightPerspective != 0 ? length(lightView) : -lightView.z;
  return (distance - lightNear) / (lightFar - lightNear);
}

// A world position's shadow-map position in level-0 texels and its linear depth.
vec3 shadowMapTexelAndDepth(vec3 world) {
  vec4 view = lightViewFromWorld * vec4(world, 1.0f);
  vec4 clip = lightClipFromView * view;
  return vec3((clip.xy / clip.w * 0.5f + 0.5f) * float(shadowMapSize), linearDepth(view.xyz));
}

// The receiver plane's depth gradient per shadow-map texel, from the rasterised triangle's own
// plane (normal n) at `world`: two steps of about a texel along the plane mapped into the shadow
// map, then solved for g in g . (texel step) = depth step. Solving the screen derivatives of uv
// and depth instead is ill-conditioned where the camera grazes a surface (the footprint's two
// axes nearly parallel in the shadow map): the far ground then shadowed itself.
vec2 receiverPlaneGradient(vec3 world, vec3 n, float step) {
  vec3 axis = abs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  vec3 tangent = normalize(cross(n, axis));
  vec3 bitangent = cross(n, tangent);
  vec3 centre = shadowMapTexelAndDepth(world);
  vec3 a = shadowMapTexelAndDepth(world + step * tangent) - centre;
  vec3 b = shadowMapTexelAndDepth(world + step * bitangent) - centre;
  float determinant = a.x * b.y - a.y * b.x;
  if (abs(determinant) <= 1e-6f * (dot(a.xy, a.xy) + dot(b.xy, b.xy))) {
    return vec2(0.0f);  // the surface is seen edge-on from the light: no plane over the texels
  }
  return vec2(b.y * a.z - a.y * b.z, -b.x * a.z + a.x * b.z) / determinant;
}

void main() {
  vec3 n = normalize(worldNormal);
  vec3 toLight = lightPerspective != 0 ? normalize(lightPosition - worldPosition) : -lightDirection;
  if (!gl_FrontFacing) n = -n;
  float cosine = max(dot(n, toLight), 0.0f);
  float offsetScale = lightPerspective != 0 ? length(lightPosition - worldPosition) : 1.0f;
  vec3 offsetPosition = worldPosition + n * normalOffset * offsetScale * (1.0f - cosine);

  vec4 lightView = lightViewFromWorld * vec4(offsetPosition, 1.0f);
  vec4 clip = lightClipFromView * lightView;
  vec2 uv = clip.xy / clip.w * 0.5f + 0.5f;
  float receiver = linearDepth(lightView.xyz);

  // Derivatives in uniform control flow: the lookup's footprint.
  vec2 uvDx = dFdx(uv);
  vec2 uvDy = dFdy(uv);
  // The triangle's geometric normal: the plane the light pass rasterised (a tessellated curved
  // surface's shading normal is not), from derivatives that stay within the triangle.
  vec3 face = cross(dFdx(worldPosition), dFdy(worldPosition));
  vec3 planeNormal = dot(face, face) > 1e-20f ? normalize(face) : n;
  vec2 depthPerTexel =
      receiverPlaneGradient(offsetPosition, planeNormal, texelWorldSize * offsetScale);

  float visibility = 1.0f;
  float diagnostic = 0.0f;
  bool inside = all(greaterThanEqual(uv, vec2(0.0f))) && all(lessThanEqual(uv, vec2(1.0f))) &&
                receiver <= 1.0f && clip.w > 0.0f;
  if (inside) {
    LookupSources sources;
    sources.unused = 0;
#if REFERENCE
    // Weights sum to 1 up to fp32 rounding. A lookup whose kernel needs more texel tests than
    // one invocation may loop over is marked -1 for the CPU twin to evaluate (Renderer).
    if (referenceTexelTests(lookupSettings(), uv, uvDx, uvDy) > kMaxReferenceTestsPerPixel) {
      visibility = -1.0f;
    } else {
      visibility = clamp(referenceVisibility(sources, lookupSettings(), uv, receiver, uvDx, uvDy,
                                             depthPerTexel), 0.0f, 1.0f);
    }
#else
    ShadowSample shadow = shadowLookup(sources, lookupSettings(), technique, params, uv, receiver,
                                       uvDx, uvDy, depthPerTexel);
    visibility = shadow.visibility;
    diagnostic = shadow.diagnostic;
#endif
  }

  // The sRGB texture reads linear; sampled in uniform control flow (its mip level needs
  // derivatives), the test comes last.
  vec4 baseColor = vec4(albedo, baseColorAlpha);
  if (hasBaseColorTexture != 0) baseColor *= texture(baseColorTexture, baseColorTexcoord);
  float lightAmount = cosine;
  if (lightPerspective != 0) lightAmount *= smoothstep(spotCosine, spotCosine + 0.05f, dot(-toLight, spotAxis));
  color = vec4(shadeLambert(baseColor.rgb, ambient, lightAmount, visibility), 1.0f);
#if REFERENCE
  if (visibility < 0.0f) {
    // Left to the CPU: the albedo and the light amount let it shade the pixel (shading.h).
    color = vec4(baseColor.rgb, 1.0f);
    diagnostic = lightAmount;
  }
#endif
  visibilityOut = visibility;
  diagnosticOut = diagnostic;
  // w: 1 inside the shadow map on a surface facing the light beyond grazing (where the shadow
  // test decides the shading), 0.5 inside but facing away or grazing, 0 outside.
  lookupOut = vec4(uv, receiver, inside ? (cosine > kGrazingCosine ? 1.0f : 0.5f) : 0.0f);
  depthPerTexelOut = depthPerTexel;
  uvDerivativesOut = vec4(uvDx, uvDy);
  if (!alphaCovers(baseColor.a, alphaCutoff)) discard;
}
