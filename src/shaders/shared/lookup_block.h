// The lookup's settings as one std140 uniform block, written by ShadowFilter (C++) and read by
// every shader that samples a filtered shadow map: the renderer's camera pass and a host's own
// fragment shader through penumbraShadow() (lib/penumbra_shadow.glsl). Explicit padding keeps
// the C++ struct byte-for-byte the std140 layout.
#ifndef PENUMBRA_SHARED_LOOKUP_BLOCK_H
#define PENUMBRA_SHARED_LOOKUP_BLOCK_H
#include "cascade_selection.h"
#include "light_depth.h"
#include "lookup_footprint.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

struct LookupBlock {
  int filterMode;          // kFilter*
  int shadowMapSize;       // level-0 texels per side
  int channelLevels;       // mip levels the lookup may use
  int anisotropy;          // [1, 16]
  int blurKernel;          // kKernelBox or kKernelGaussian
  int zmaxLevels;          // ESM's Z-max pyramid levels (0: none)
  int layersPerCascade;    // channel-texture layers per map layer
  int channelsPerCascade;  // technique channels per map layer (summed-area table rows)
  int depthSamples;        // the unfiltered depth's MSAA samples (1: none)
  // How a host's shadowCoord.z (window depth of the host's light projection) becomes the
  // linear metric the map holds (windowDepthToLinear): 1 perspective, 0 orthographic or linear.
  int receiverPerspective;
  float receiverNear;
  float receiverFar;
  // Per map layer: the prefilter's radius (taps), its Gaussian sigma, and layer 0's texel over
  // this layer's (the kernel's world width kept across cascades); w unused.
  vec4 layerKernel[kMaxCascades];
};

// One map layer's LookupSettings from the block.
PENUMBRA_INLINE LookupSettings lookupSettingsFromBlock(LookupBlock b, int layer) {
  LookupSettings s;
  s.filterMode = b.filterMode;
  s.shadowMapSize = b.shadowMapSize;
  s.channelLevels = b.channelLevels;
  s.anisotropy = b.anisotropy;
  s.blurKernel = b.blurKernel;
  s.blurRadius = int(b.layerKernel[layer].x);
  s.blurSigma = b.layerKernel[layer].y;
  s.zmaxLevels = b.zmaxLevels;
  s.kernelScale = b.layerKernel[layer].z;
  return s;
}

// A window depth in [0, 1] of the light's projection as the linear metric of light_depth.h,
// measured along the light's axis: an orthographic projection's window depth is that metric
// already; a perspective one's is hyperbolic, z = n f / (f - d (f - n)).
PENUMBRA_INLINE float windowDepthToLinear(float windowDepth, int perspective, float nearDistance,
                                          float farDistance) {
  if (perspective == 0) return windowDepth;
  float distance =
      nearDistance * farDistance / (farDistance - windowDepth * (farDistance - nearDistance));
  return (distance - nearDistance) / (farDistance - nearDistance);
}

PENUMBRA_END_SHARED
#endif
