// penumbraShadow(): a filtered shadow map's visibility in a host's own fragment shader
// (docs/integration.md). ShadowFilter::filter makes the map, ShadowFilter::bind binds it and
// ShadowFilter::shaderPreamble gives the #defines this file needs (technique, variant,
// bindings). The lookup itself is the renderer's: shared/shadow_lookup.h.
//
// shadowCoord: the receiver in the light's map, as the host's own light projection puts it:
// xy in [0, 1] over the map, z the window depth the host's depth texture would hold there (or
// penumbra's linear depth when the map was given as LinearDepth). Visibility is 1 outside the
// map. A hard light (no light size): soft shadows are the renderer's.
#ifndef PENUMBRA_LIB_PENUMBRA_SHADOW_GLSL
#define PENUMBRA_LIB_PENUMBRA_SHADOW_GLSL
// penumbraShadow passes a hard light: the soft paths stay out of the lookup's source.
#ifndef PENUMBRA_SOFT_SHADOWS
#define PENUMBRA_SOFT_SHADOWS 0
#endif
#include "lookup_access.glsl"
#include "../shared/receiver_plane.h"

// The receiver's depth in the map's linear metric.
float penumbraReceiverDepth(float windowDepth) {
  return windowDepthToLinear(windowDepth, penumbraLookup.receiverPerspective,
                             penumbraLookup.receiverNear, penumbraLookup.receiverFar);
}

// Layer `layer` of the map (a cascade, a point light's face); dx, dy: shadowCoord's screen
// derivatives (the lookup's footprint: mip level, anisotropy, PCF's kernel); depthPerTexel: the
// receiver plane's linear-depth gradient per texel (0: flat, the techniques' bias only).
float penumbraShadow(int layer, vec3 shadowCoord, vec2 dx, vec2 dy, vec2 depthPerTexel) {
  vec2 uv = shadowCoord.xy;
  if (any(lessThan(uv, vec2(0.0f))) || any(greaterThan(uv, vec2(1.0f))) ||
      shadowCoord.z > 1.0f) {
    return 1.0f;
  }
  LookupSources sources;
  sources.cascade = layer;
  SoftLight hard;
  hard.size = 0.0f;
  hard.perspective = penumbraLookup.receiverPerspective;
  hard.nearDistance = penumbraLookup.receiverNear;
  hard.farDistance = penumbraLookup.receiverFar;
  hard.texelWorldSize = 1.0f;
  hard.maxWidthTexels = kMaxSoftWidthTexels;
  ShadowSample s =
      shadowLookup(sources, lookupSettings(layer), penumbraTechnique, lookupParams(), uv,
                   penumbraReceiverDepth(shadowCoord.z), dx, dy, depthPerTexel, hard);
  return s.visibility;
}

// Layer 0, a flat receiver: the signature engines know.
float penumbraShadow(vec3 shadowCoord, vec2 dx, vec2 dy) {
  return penumbraShadow(0, shadowCoord, dx, dy, vec2(0.0f));
}

// Fragment shaders only (dFdx): a compute shader defines PENUMBRA_NO_DERIVATIVES and passes
// the footprint itself.
#ifndef PENUMBRA_NO_DERIVATIVES
// Everything from screen derivatives: the footprint, and the receiver plane's depth gradient
// solved from the derivatives of uv and depth (receiver-plane depth bias). Call it in uniform
// control flow, like any function that takes derivatives.
float penumbraShadow(int layer, vec3 shadowCoord) {
  vec2 dx = dFdx(shadowCoord.xy);
  vec2 dy = dFdy(shadowCoord.xy);
  float depthDx = dFdx(penumbraReceiverDepth(shadowCoord.z));
  float depthDy = dFdy(penumbraReceiverDepth(shadowCoord.z));
  vec2 depthPerUv = solveDepthGradient(vec3(dx, depthDx), vec3(dy, depthDy));
  vec2 depthPerTexel = depthPerUv / float(penumbraLookup.shadowMapSize);
  return penumbraShadow(layer, shadowCoord, dx, dy, depthPerTexel);
}

float penumbraShadow(vec3 shadowCoord) {
  return penumbraShadow(0, shadowCoord);
}
#endif

#endif
