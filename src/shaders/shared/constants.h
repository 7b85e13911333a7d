// Identifiers and limits shared by the C++ core and the shaders: technique ids, storage formats,
// channel reductions. The C++ enums in include/penumbra/ are checked against these values.
#ifndef PENUMBRA_SHARED_CONSTANTS_H
#define PENUMBRA_SHARED_CONSTANTS_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

const float kPi = 3.14159265358979f;

const int kTechniqueHard = 0;
const int kTechniquePcf = 1;
const int kTechniqueVsm = 2;
const int kTechniqueLvsm = 3;
const int kTechniqueEvsm2 = 4;
const int kTechniqueEvsm4 = 5;
const int kTechniqueEsm = 6;
const int kTechniqueCsm = 7;
const int kTechniquePowerCdf = 8;
const int kTechniqueMsm = 9;
const int kTechniqueCount = 10;

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
