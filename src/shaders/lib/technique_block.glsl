// The technique and its parameter block, as every pass that runs the shared math sees them.
#ifndef PENUMBRA_LIB_TECHNIQUE_BLOCK_GLSL
#define PENUMBRA_LIB_TECHNIQUE_BLOCK_GLSL
#include "../shared/technique_dispatch.h"

layout(std140, binding = 0) uniform TechniqueBlock { TechniqueParams params; };
uniform int technique;

#endif
