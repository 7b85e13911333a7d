// The technique and its parameter block, as every pass that runs the shared math sees them.
#ifndef PENUMBRA_LIB_TECHNIQUE_BLOCK_GLSL
#define PENUMBRA_LIB_TECHNIQUE_BLOCK_GLSL
#ifdef TECHNIQUE_ID
// The other techniques' lookup paths leave the source (shared/constants.h), from here on.
#undef PENUMBRA_COMPILES_TECHNIQUE
#define PENUMBRA_COMPILES_TECHNIQUE(t) (TECHNIQUE_ID == (t))
#endif
#include "../shared/technique_dispatch.h"

#ifndef PENUMBRA_PARAMETER_BLOCK
#define PENUMBRA_PARAMETER_BLOCK 0
#endif
#ifndef PENUMBRA_LAYER_RANGE_BLOCK
#define PENUMBRA_LAYER_RANGE_BLOCK 1
#endif
layout(std140, binding = PENUMBRA_PARAMETER_BLOCK) uniform TechniqueBlock {
  TechniqueParams penumbraParams;
};
// The encode's per-texel-layer ranges (texelLayerRangeTable), read from the block by the layer's
// index: computed in every invocation they cost LVSM's encode 7x a copy on llvmpipe.
layout(std140, binding = PENUMBRA_LAYER_RANGE_BLOCK) uniform TexelLayerRangeBlock {
  TexelLayerRangeTable penumbraRangeTable;
};
// The renderer compiles one variant per technique, so the dispatcher folds to one branch.
#ifdef TECHNIQUE_ID
const int penumbraTechnique = TECHNIQUE_ID;
#else
uniform int penumbraTechnique;
#endif

#endif
