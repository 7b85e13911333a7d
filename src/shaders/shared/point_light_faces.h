// Point lights: six perspective faces, one shadow-map layer each, chosen per receiver by the
// major axis of (receiver - light). Each face's frustum is wider than 90 degrees by a guard band
// of texels on every side, so a prefilter kernel or a lookup near the face's 90-degree edge still
// reads real depths (what the neighbouring face also sees) instead of the layer's clamped border:
// the band stands in for a seamless cube map's cross-face filtering (docs/renderer.md). Shared by
// the camera pass, the light pass's matrices (penumbra/point_light.h) and the CPU tests.
#ifndef PENUMBRA_SHARED_POINT_LIGHT_FACES_H
#define PENUMBRA_SHARED_POINT_LIGHT_FACES_H
#include "light_depth.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

const int kPointLightFaces = 6;

// Face f looks along +x, -x, +y, -y, +z, -z for f = 0..5 (GL's cube-map face order).
PENUMBRA_INLINE int pointLightFace(vec3 fromLight) {
  vec3 a = abs(fromLight);
  if (a.x >= a.y && a.x >= a.z) return fromLight.x >= 0.0f ? 0 : 1;
  if (a.y >= a.z) return fromLight.y >= 0.0f ? 2 : 3;
  return fromLight.z >= 0.0f ? 4 : 5;
}

// A face's orthonormal frame: `forward` is the axis it looks along; right x up = -forward, as a
// GL view whose camera looks down -z (right = +x, up = +y of the face's view space).
struct PointFaceFrame {
  vec3 forward;
  vec3 right;
  vec3 up;
};

PENUMBRA_INLINE PointFaceFrame pointLightFaceFrame(int face) {
  float sign = (face % 2) == 0 ? 1.0f : -1.0f;
  int axis = face / 2;
  PointFaceFrame f;
  f.forward = vec3(axis == 0 ? sign : 0.0f, axis == 1 ? sign : 0.0f, axis == 2 ? sign : 0.0f);
  // Any up not parallel to forward; y for the side faces, z for the top and bottom.
  vec3 up = axis == 1 ? vec3(0.0f, 0.0f, 1.0f) : vec3(0.0f, 1.0f, 0.0f);
  f.right = normalize(cross(f.forward, up));
  f.up = cross(f.right, f.forward);
  return f;
}

// The tangent of a face's half field of view: the 90-degree face (tangent 1) spans the map's
// size - 2 * guard central texels, so guard texels lie beyond each of its edges:
// 0.5 + 0.5 / t = 1 - guard / size, i.e. t = size / (size - 2 * guard).
PENUMBRA_INLINE float pointFaceTangent(int shadowMapSize, int guardTexels) {
  return float(shadowMapSize) / float(shadowMapSize - 2 * guardTexels);
}

// Texels of guard band each side of a face: everything a lookup at the face's 90-degree edge may
// read beyond it. The prefilter's blur reaches `blurRadius` texels (its kernel clamps at the
// layer's border, which must stay beyond the data the edge's texels average); the lookup's own
// taps reach `lookupReach` texels further (a bilinear tap: 1; PCF of radius r: r + 1); one more
// texel because the edge lies anywhere within its texel. A light with a size adds its soft
// lookups' reach, `softWidthTexels` (pointLightSoftWidthTexels, 0 when hard): every tap lies
// within one width w of the lookup (the blocker search and PCSS's kernel within w/2 + 1, the
// summed-area box within w/2 + 1, the mip probes within 3w/8 plus a bilinear tap at the next
// level of a probe's lod, 2 w / (4 sqrt 3): 0.67 w). Mip-mapped lookups at level L read
// 2^L-texel blocks: levels whose blocks exceed the band read the clamped border at the edge
// (minified views of a face's edge only; docs/renderer.md).
PENUMBRA_INLINE int pointFaceGuardTexels(int blurRadius, int lookupReach, int softWidthTexels) {
  return blurRadius + lookupReach + 1 + softWidthTexels;
}

// The unit direction from the light through `uv` of face `face`: pointFaceUv's inverse (with
// the distance from the light it gives the position; the area-light reference's receivers).
PENUMBRA_INLINE vec3 pointFaceDirection(int face, vec2 uv, float tangent) {
  PointFaceFrame f = pointLightFaceFrame(face);
  float x = (uv.x * 2.0f - 1.0f) * tangent;
  float y = (uv.y * 2.0f - 1.0f) * tangent;
  return normalize(f.forward + x * f.right + y * f.up);
}

// Where a position relative to the light lands in face `face`'s map: uv in [0, 1] over the guarded
// face (the 90-degree face is [g/size, 1 - g/size]); the distance along the face's axis in the
// third component (> 0 in front of the face). `tangent` is pointFaceTangent's.
PENUMBRA_INLINE vec3 pointFaceUv(int face, vec3 fromLight, float tangent) {
  PointFaceFrame f = pointLightFaceFrame(face);
  float along = dot(fromLight, f.forward);
  float safe = max(along, 1e-30f);
  vec2 plane = vec2(dot(fromLight, f.right), dot(fromLight, f.up)) / (safe * tangent);
  return vec3(plane.x * 0.5f + 0.5f, plane.y * 0.5f + 0.5f, along);
}

// The change of pointFaceUv's uv for a small step `delta` away from `fromLight`, through the
// projection's derivative at `fromLight` (d(x/a) = (dx a - x da) / a^2): the lookup's footprint
// in the pixel's own face. Differencing the uvs of the neighbouring pixels' positions instead
// fails at silhouettes, where a neighbour on another surface may lie behind the face's plane.
PENUMBRA_INLINE vec2 pointFaceUvStep(int face, vec3 fromLight, vec3 delta, float tangent) {
  PointFaceFrame f = pointLightFaceFrame(face);
  float along = max(dot(fromLight, f.forward), 1e-30f);
  float alongStep = dot(delta, f.forward);
  float x = dot(fromLight, f.right);
  float y = dot(fromLight, f.up);
  float scale = 0.5f / (tangent * along * along);
  return vec2((dot(delta, f.right) * along - x * alongStep) * scale,
              (dot(delta, f.up) * along - y * alongStep) * scale);
}

// Linear depth of a point light: the distance from the light over [near, far], like a spot
// light's (thesis §4.1.3).
PENUMBRA_INLINE float pointLightDepth(vec3 fromLight, float nearDistance, float farDistance) {
  return lightLinearDepth(fromLight, true, nearDistance, farDistance);
}

PENUMBRA_END_SHARED
#endif
