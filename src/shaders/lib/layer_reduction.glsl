// The reduction of channel `c` of texel layer `layer`, resolved at compile time where the CPU
// could (reductionDefines in src/gl/shadow_map_filter.cpp): FORCE_REDUCTION for every channel
// (the Z-max pyramid), LAYER_REDUCTIONS for a technique with one texel layer (every cascade's
// layer alike), else the technique's own
// dispatcher at run time (several layers with mixed reductions: the layered power CDF).
// ALL_MEAN, when set, tells the passes to sum whole texels instead (accumulateMeanTexel).
#ifndef PENUMBRA_LIB_LAYER_REDUCTION_GLSL
#define PENUMBRA_LIB_LAYER_REDUCTION_GLSL
#include "technique_block.glsl"
#include "../shared/channel_reduction.h"

#ifndef ALL_MEAN
#define ALL_MEAN 0
#endif

int layerChannelReduction(int layer, int c) {
#if defined(FORCE_REDUCTION)
  return FORCE_REDUCTION;
#elif defined(LAYER_REDUCTIONS)
  return LAYER_REDUCTIONS[c];
#else
  // `layer` may count every cascade's layers (the mip pass runs over the whole array): the
  // channel is the one within the cascade. A layer's unused components (beyond the technique's
  // channels) are reduced as means and never read.
  int count = techniqueChannelCount(penumbraTechnique, penumbraParams);
  int channel = 4 * (layer % ((count + 3) / 4)) + c;
  return channel < count
             ? channelReduction(penumbraTechnique, channel, penumbraParams)
             : kReduceMean;
#endif
}

#endif
