// Camera pass: the pixel's cascade (shared/cascade_selection.h) or a point light's face
// (shared/point_light_faces.h: the cascades' layers are then the six faces), receiver depth in light space
// (with normal offset), the technique's visibility (blended with the next cascade in the blend
// band), and Lambert + ambient shading of the base colour (factor x sRGB texture). Writes colour
// and, when asked, the float visibility and the diagnostic (DIAGNOSTICS) and the lookup's inputs
// for the CPU twin (LOOKUP_INPUTS). Alpha-masked surfaces are cut
// out by the same test as in the light pass, in a variant of their own (ALPHA_TEST,
// lib/material.glsl).
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
// 1: write the visibility and the diagnostic (targets 1-2: the frame reads either back, or the
// lookup's inputs follow them); 0: compiled out, so that a frame nobody reads them from
// (RenderSettings::readBack of the colour alone or nothing: bench's and tune's timed frames)
// writes its colour alone.
#ifndef DIAGNOSTICS
#define DIAGNOSTICS 1
#endif
// 1: write the lookup's inputs (targets 3-6, RenderSettings::lookupInputs); 0: compiled out, so
// the pass neither computes what only they need nor stores 48 bytes more per pixel.
#ifndef LOOKUP_INPUTS
#define LOOKUP_INPUTS 1
#endif
#if LOOKUP_INPUTS && !DIAGNOSTICS
#error "the lookup's inputs (locations 3-6) come with the diagnostics (locations 1-2)"
#endif
// The light's kind and softness are compiled in (CameraPass::render: one program each), so that
// a pixel does not carry the other kinds' paths: a GPU sizes its registers for the largest path
// a shader holds, taken or not.
#ifndef LIGHT_PERSPECTIVE
#define LIGHT_PERSPECTIVE 0
#endif
#ifndef POINT_LIGHT
#define POINT_LIGHT 0
#endif
#ifndef CASCADED
#define CASCADED 0
#endif
#ifndef SOFT_LIGHT
#define SOFT_LIGHT 0
#endif
// 1: tint each pixel by its cascade (RenderSettings::overlay). Compiled in: as a uniform, llvmpipe
// ran the tint (a palette indexed per pixel) for every pixel of every frame, up to 0.08 of the
// pass's ratio to its minimal lookup (docs/results/passes-llvmpipe-2026-12-06-paired.md).
#ifndef CASCADE_OVERLAY
#define CASCADE_OVERLAY 0
#endif
// A hard light's variants leave the soft paths out of the shared lookup's source.
#define PENUMBRA_SOFT_SHADOWS SOFT_LIGHT
#include "../lib/lookup_access.glsl"
#include "../lib/material.glsl"
#include "../shared/point_light_faces.h"
#include "../shared/receiver_plane.h"
#include "../shared/shading.h"

in vec3 worldPosition;
in vec3 worldNormal;
in vec2 baseColorTexcoord;

uniform mat4 cameraViewFromWorld;  // view depth selects the cascade
uniform mat4 lightViewFromWorld;
uniform mat4 lightClipFromView;    // one map: its projection; cascades: unused (boxes instead)
const int lightPerspective = LIGHT_PERSPECTIVE;
uniform float lightNear;
uniform float lightFar;
uniform vec3 lightDirection;  // directional: the way light travels
uniform vec3 lightPosition;   // spot
uniform vec3 spotAxis;        // spot: unit direction from the light to its target
uniform float spotCosine;     // spot: cos(half cone angle)
const int pointLight = POINT_LIGHT;  // 1: six faces, chosen per pixel by the major axis
uniform float pointLightTangent;  // tan of a face's half field of view (guard band included)
uniform float normalOffsetTexels;
uniform float lightSize;  // Light::size: 0 hard, else soft (shared/soft_shadow.h)
// 0: one map, uv through lightClipFromView. 1: cascades, boxes on the light's view plane.
const int cascaded = CASCADED;
uniform int cascadeCount;
// One map (CascadeFrame of one cascade, no point light) has one cascade, compiled in: the
// selection loop and the cascade arrays' indices become constants.
#if CASCADED || POINT_LIGHT
#define FRAME_CASCADES cascadeCount
#else
#define FRAME_CASCADES 1
#endif
uniform vec4 cascadeBoxes[kMaxCascades];   // one map: (0, 0, 1, 1) over its uv
uniform float cascadeTexelWorldSize[kMaxCascades];  // per unit distance for spot lights
uniform float cascadeStart;
uniform vec4 cascadeEnds0;
uniform vec4 cascadeEnds1;
uniform float cascadeBlendBand;
uniform float ambient;

layout(location = 0) out vec4 color;
#if DIAGNOSTICS
layout(location = 1) out float visibilityOut;
layout(location = 2) out float diagnosticOut;  // ShadowSample's; -1 where nothing is drawn
#endif
#if LOOKUP_INPUTS
layout(location = 3) out vec4 lookupOut;       // shadow-map uv, receiver depth, where (see main)
layout(location = 4) out vec2 depthPerTexelOut;  // the receiver plane's depth gradient per texel
layout(location = 5) out vec4 uvDerivativesOut;  // dFdx(uv), dFdy(uv): the lookup's footprint
layout(location = 6) out vec2 cascadeOut;        // the deciding cascade (-1: none) and blend
#endif

// A point light's face for this pixel: every position of the pixel's lookup (its receiver-plane
// steps, its neighbours' for the footprint) is projected into it, so nothing straddles faces.
int pointFace = 0;

float linearDepth(vec3 lightView) {
  return lightLinearDepth(lightView, lightPerspective != 0, lightNear, lightFar);
}

// A world position on the light's plane (one map: its uv; cascades: light-view x, y), its
// linear depth, and its clip w (in front of a spot light when > 0).
vec4 lightPlaneAndDepth(vec3 world) {
  if (pointLight != 0) {
    vec3 fromLight = world - lightPosition;
    vec3 face = pointFaceUv(pointFace, fromLight, pointLightTangent);
    return vec4(face.x, face.y, pointLightDepth(fromLight, lightNear, lightFar), face.z);
  }
  vec4 view = lightViewFromWorld * vec4(world, 1.0f);
  if (cascaded != 0) return vec4(view.x, view.y, linearDepth(view.xyz), 1.0f);
  vec4 clip = lightClipFromView * view;
  return vec4(clip.xy / clip.w * 0.5f + 0.5f, linearDepth(view.xyz), clip.w);
}

// How lightPlaneAndDepth(world).xyz changes along `direction` (world units) for a directional
// light, whose maps are affine (an orthographic projection: clip w is 1): their linear parts
// applied to the direction. The differences of full evaluations give the same up to rounding,
// but lose digits to cancellation and cost the centre's evaluation, the translations and the
// divisions (docs/results/passes-llvmpipe-2026-12-06-diagnostics.md).
vec3 lightPlaneAndDepthAlong(vec3 direction) {
  vec3 view = mat3(lightViewFromWorld) * direction;
  vec2 plane = cascaded != 0 ? view.xy : (lightClipFromView * vec4(view, 0.0f)).xy * 0.5f;
  return vec3(plane, -view.z / (lightFar - lightNear));
}

// The receiver plane's depth gradient per unit of the light's plane, from the rasterised
// triangle's own plane (normal n) at `world`: two steps of about a texel along the plane mapped
// onto the light's plane, then solved for g in g . (plane step) = depth step. Solving the screen
// derivatives of uv and depth instead is ill-conditioned where the camera grazes a surface (the
// footprint's two axes nearly parallel in the shadow map): the far ground then shadowed itself.
vec2 receiverPlaneGradient(vec3 world, vec3 n, float step) {
  vec3 axis = abs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  vec3 tangent = normalize(cross(n, axis));
  vec3 bitangent = cross(n, tangent);
  if (lightPerspective == 0 && pointLight == 0) {
    vec3 a = lightPlaneAndDepthAlong(step * tangent);
    vec3 b = lightPlaneAndDepthAlong(step * bitangent);
    return solveDepthGradient(a, b);
  }
  vec3 centre = lightPlaneAndDepth(world).xyz;
  vec3 a = lightPlaneAndDepth(world + step * tangent).xyz - centre;
  vec3 b = lightPlaneAndDepth(world + step * bitangent).xyz - centre;
  return solveDepthGradient(a, b);
}

// One cascade's lookup of the pixel: visibility (-1: left to the CPU) and diagnostic.
vec2 cascadeVisibility(int cascade, vec2 uv, vec2 uvDx, vec2 uvDy, vec2 depthPerTexel,
                       float receiver) {
  LookupSources sources;
  sources.cascade = cascade;
  LookupSettings settings = lookupSettings(cascade);
#if REFERENCE
  // Weights sum to 1 up to fp32 rounding. A lookup whose kernel needs more texel tests than
  // one invocation may loop over is marked -1 for the CPU twin to evaluate (Renderer).
  if (referenceLeftToCpu(settings, uv, uvDx, uvDy)) {
    return vec2(-1.0f, 0.0f);
  }
  return vec2(clamp(referenceVisibility(sources, settings, uv, receiver, uvDx, uvDy,
                                        depthPerTexel), 0.0f, 1.0f), 0.0f);
#else
  SoftLight light;
  light.size = SOFT_LIGHT != 0 ? lightSize : 0.0f;
  light.perspective = lightPerspective;
  light.nearDistance = lightNear;
  light.farDistance = lightFar;
  light.texelWorldSize = cascadeTexelWorldSize[cascade];
  light.maxWidthTexels =
      pointLight != 0 ? pointLightSoftWidthTexels(penumbraLookup.shadowMapSize)
                      : kMaxSoftWidthTexels;
  ShadowSample shadow = shadowLookup(sources, settings, penumbraTechnique, lookupParams(), uv,
                                     receiver, uvDx, uvDy, depthPerTexel, light);
  return vec2(shadow.visibility, shadow.diagnostic);
#endif
}

vec3 cascadeTint(int cascade) {
  const vec3 palette[kMaxCascades] = vec3[](vec3(1.0f, 0.45f, 0.45f), vec3(0.45f, 1.0f, 0.45f),
      vec3(0.5f, 0.6f, 1.0f), vec3(1.0f, 1.0f, 0.4f), vec3(1.0f, 0.45f, 1.0f),
      vec3(0.4f, 1.0f, 1.0f), vec3(1.0f, 0.7f, 0.35f), vec3(0.75f, 0.75f, 0.75f));
  return palette[cascade];
}

void main() {
  vec3 n = normalize(worldNormal);
  vec3 toLight = lightPerspective != 0 ? normalize(lightPosition - worldPosition) : -lightDirection;
  if (!gl_FrontFacing) n = -n;
  float cosine = max(dot(n, toLight), 0.0f);

  float viewDepth = -(cameraViewFromWorld * vec4(worldPosition, 1.0f)).z;
  CascadeChoice choice = selectCascade(viewDepth, cascadeStart, cascadeEnds0, cascadeEnds1,
                                       FRAME_CASCADES, cascadeBlendBand);
  int cascade = min(choice.index, FRAME_CASCADES - 1);
  vec4 box = cascadeBoxes[cascade];

  float offsetScale = lightPerspective != 0 ? length(lightPosition - worldPosition) : 1.0f;
  float texelWorld = cascadeTexelWorldSize[cascade] * offsetScale;
  vec3 offsetPosition = worldPosition + n * normalOffsetTexels * texelWorld * (1.0f - cosine);
  if (pointLight != 0) {
    pointFace = pointLightFace(offsetPosition - lightPosition);
    cascade = pointFace;
    box = cascadeBoxes[cascade];
  }
  vec4 planeAndDepth = lightPlaneAndDepth(offsetPosition);
  vec2 plane = planeAndDepth.xy;
  float receiver = planeAndDepth.z;

  // Derivatives in uniform control flow: the lookup's footprint on the light's plane. A point
  // light's neighbouring pixels may lie in another face: the position's derivatives go through
  // the derivative of this pixel's face projection instead of differencing uvs of two faces.
  vec2 planeDx = dFdx(plane);
  vec2 planeDy = dFdy(plane);
  vec3 positionDx = dFdx(offsetPosition);
  vec3 positionDy = dFdy(offsetPosition);
  if (pointLight != 0) {
    vec3 fromLight = offsetPosition - lightPosition;
    planeDx = pointFaceUvStep(pointFace, fromLight, positionDx, pointLightTangent);
    planeDy = pointFaceUvStep(pointFace, fromLight, positionDy, pointLightTangent);
  }
  // The triangle's geometric normal: the plane the light pass rasterised (a tessellated curved
  // surface's shading normal is not), from derivatives that stay within the triangle.
  vec3 face = cross(dFdx(worldPosition), dFdy(worldPosition));
  vec3 planeNormal = dot(face, face) > 1e-20f ? normalize(face) : n;
  vec2 depthPerUnit = receiverPlaneGradient(offsetPosition, planeNormal, texelWorld);

  vec2 uv = cascadeUv(plane, box, 0);
  vec2 uvDx = cascadeUv(planeDx, box, 1);
  vec2 uvDy = cascadeUv(planeDy, box, 1);
  vec2 depthPerTexel = cascadeDepthPerTexel(depthPerUnit, box, penumbraLookup.shadowMapSize);

  float visibility = 1.0f;
  float diagnostic = 0.0f;
  if (pointLight != 0) {
    choice.index = pointFace;
    choice.blend = 0.0f;
  }
  bool inside = choice.index < FRAME_CASCADES && all(greaterThanEqual(uv, vec2(0.0f))) &&
                all(lessThanEqual(uv, vec2(1.0f))) && receiver <= 1.0f && planeAndDepth.w > 0.0f;
  if (inside) {
    vec2 result = cascadeVisibility(cascade, uv, uvDx, uvDy, depthPerTexel, receiver);
    visibility = result.x;
    diagnostic = result.y;
#if CASCADED
    // One map (and a point light's faces) has no blend band (selectCascade's last cascade fades
    // into nothing): compiled out there, this second lookup doubled the pass's compile time.
    if (choice.blend > 0.0f) {
      // The blend band: the next cascade's lookup of the same point, mixed in (its box covers
      // this band by construction, penumbra/cascades.h).
      vec4 next = cascadeBoxes[cascade + 1];
      vec2 blended = cascadeVisibility(cascade + 1, cascadeUv(plane, next, 0),
                                       cascadeUv(planeDx, next, 1), cascadeUv(planeDy, next, 1),
                                       cascadeDepthPerTexel(depthPerUnit, next,
                                                            penumbraLookup.shadowMapSize),
                                       receiver);
      visibility = visibility < 0.0f || blended.x < 0.0f
                       ? -1.0f
                       : mix(visibility, blended.x, choice.blend);
    }
#endif
  }

  // The sRGB texture reads linear; sampled in uniform control flow (its mip level needs
  // derivatives), the test comes last.
  vec4 baseColor = materialBaseColor(baseColorTexcoord);
  float lightAmount = cosine;
  if (lightPerspective != 0 && pointLight == 0) lightAmount *= spotConeFalloff(dot(-toLight, spotAxis), spotCosine);
  vec3 surface = baseColor.rgb;
  if (CASCADE_OVERLAY != 0 && choice.index < FRAME_CASCADES) {
    vec3 tint = cascadeTint(cascade);
    if (choice.blend > 0.0f) tint = mix(tint, cascadeTint(cascade + 1), choice.blend);
    surface *= tint;
  }
  color = vec4(shadeLambert(surface, ambient, lightAmount, visibility), 1.0f);
#if REFERENCE
  if (visibility < 0.0f) {
    // Left to the CPU: the albedo and the light amount let it shade the pixel (shading.h).
    color = vec4(surface, 1.0f);
    diagnostic = lightAmount;
  }
#endif
#if DIAGNOSTICS
  visibilityOut = visibility;
  diagnosticOut = diagnostic;
#endif
#if LOOKUP_INPUTS
  // w: 1 inside the shadow map on a surface facing the light beyond grazing (where the shadow
  // test decides the shading), 0.5 inside but facing away or grazing, 0 outside.
  lookupOut = vec4(uv, receiver, inside ? (cosine > kGrazingCosine ? 1.0f : 0.5f) : 0.0f);
  depthPerTexelOut = depthPerTexel;
  uvDerivativesOut = vec4(uvDx, uvDy);
  cascadeOut = vec2(inside ? float(cascade) : -1.0f, inside ? choice.blend : 0.0f);
#endif
#if ALPHA_TEST
  if (!alphaCovers(baseColor.a, alphaCutoff)) discard;
#endif
}
