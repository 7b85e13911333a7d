// Identifiers and limits shared by the C++ core and the shaders: technique ids, storage formats,
// channel reductions. The C++ enums in include/penumbra/ are checked against these values.
#ifndef PENUMBRA_SHARED_CONSTANTS_H
#define PENUMBRA_SHARED_CONSTANTS_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

const float kPi = 3.14159265358979f;

// The technique ids as preprocessor numbers too, for PENUMBRA_COMPILES_TECHNIQUE.
#define PENUMBRA_TECHNIQUE_HARD 0
#define PENUMBRA_TECHNIQUE_PCF 1
#define PENUMBRA_TECHNIQUE_VSM 2
#define PENUMBRA_TECHNIQUE_LVSM 3
#define PENUMBRA_TECHNIQUE_EVSM2 4
#define PENUMBRA_TECHNIQUE_EVSM4 5
#define PENUMBRA_TECHNIQUE_ESM 6
#define PENUMBRA_TECHNIQUE_CSM 7
#define PENUMBRA_TECHNIQUE_POWER_CDF 8
#define PENUMBRA_TECHNIQUE_MSM 9
const int kTechniqueHard = PENUMBRA_TECHNIQUE_HARD;
const int kTechniquePcf = PENUMBRA_TECHNIQUE_PCF;
const int kTechniqueVsm = PENUMBRA_TECHNIQUE_VSM;
const int kTechniqueLvsm = PENUMBRA_TECHNIQUE_LVSM;
const int kTechniqueEvsm2 = PENUMBRA_TECHNIQUE_EVSM2;
const int kTechniqueEvsm4 = PENUMBRA_TECHNIQUE_EVSM4;
const int kTechniqueEsm = PENUMBRA_TECHNIQUE_ESM;
const int kTechniqueCsm = PENUMBRA_TECHNIQUE_CSM;
const int kTechniquePowerCdf = PENUMBRA_TECHNIQUE_POWER_CDF;
const int kTechniqueMsm = PENUMBRA_TECHNIQUE_MSM;
const int kTechniqueCount = 10;

// Whether a shader's source keeps technique t's own lookup paths: a shader compiled for one
// technique (lib/technique_block.glsl defines this macro for the renderer's variants) leaves the
// other techniques' out, where C++ and a shader compiled for every technique keep them all. The
// paths left out were folded away after inlining, but the GLSL compiler paid for them
// (docs/renderer.md, the camera pass's variants). This header must not name the define itself:
// ProgramCache specialises every shader whose source names it (ProgramCacheTest).
#ifndef PENUMBRA_COMPILES_TECHNIQUE
#define PENUMBRA_COMPILES_TECHNIQUE(t) 1
#endif

// Storage formats of the encoded channels. Encoders keep values in the range the format holds.
const int kStorageFloat32 = 0;
const int kStorageFloat16 = 1;
const int kStorageUnorm16 = 2;
const int kStorageUnorm8 = 3;

// How a channel is combined when it is filtered (blur, mips, summed-area tables).
const int kReduceMean = 0;
const int kReduceMin = 1;
const int kReduceMax = 2;
const int kReduceLogMeanExp = 3;  // log-space mean of exp(c*v): ESM log-space filtering (Salvi)

// Layered techniques (LVSM, layered power-CDF) hold at most this many layers.
const int kMaxLayers = 16;
// Most channels any technique needs: layered power-CDF, 16 layers x (min, max, mean).
const int kMaxChannels = 48;
const int kMaxTexelLayers = kMaxChannels / 4;  // four channels per texel

PENUMBRA_END_SHARED
#endif
