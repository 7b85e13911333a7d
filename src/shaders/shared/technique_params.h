// Every technique's parameters in one block, so one uniform/storage block (and one C++ struct)
// carries the settings of a frame. Defaults come from each technique's header.
#ifndef PENUMBRA_SHARED_TECHNIQUE_PARAMS_H
#define PENUMBRA_SHARED_TECHNIQUE_PARAMS_H
#include "csm.h"
#include "esm.h"
#include "evsm.h"
#include "hard.h"
#include "lvsm.h"
#include "msm.h"
#include "pcf.h"
#include "power_cdf.h"
#include "prelude.h"
#include "vsm.h"
PENUMBRA_BEGIN_SHARED

struct TechniqueParams {
  HardParams hard;
  PcfParams pcf;
  VsmParams vsm;
  LvsmParams lvsm;
  EvsmParams evsm;  // shared by EVSM2 (positive warp only) and EVSM4
  EsmParams esm;
  CsmParams csm;
  PowerCdfParams powerCdf;
  MsmParams msm;
};

PENUMBRA_INLINE TechniqueParams defaultTechniqueParams() {
  TechniqueParams p;
  p.hard = hardDefaultParams();
  p.pcf = pcfDefaultParams();
  p.vsm = vsmDefaultParams();
  p.lvsm = lvsmDefaultParams();
  p.evsm = evsmDefaultParams();
  p.esm = esmDefaultParams();
  p.csm = csmDefaultParams();
  p.powerCdf = powerCdfDefaultParams();
  p.msm = msmDefaultParams();
  return p;
}

PENUMBRA_END_SHARED
#endif
