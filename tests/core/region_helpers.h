// Test helpers: a technique's visibility over a filter region given as (depth, weight) pairs.
#pragma once

#include <vector>

#include "penumbra/depth_distribution.h"
#include "penumbra/technique.h"

namespace penumbra::testing {

// Visibility of a receiver at `receiver` over a region made of `occluders` plus the receiver
// plane filling the remaining weight.
inline float visibility(Technique technique, const TechniqueParams& params,
                        const std::vector<DepthSample>& occluders, float receiver) {
  return evaluateOnRegion(technique, params, regionWithReceiver(occluders, receiver), receiver);
}

// Float32 storage everywhere, so tests of formulas see no quantisation unless they ask for it.
inline TechniqueParams float32Params() {
  TechniqueParams p = defaultTechniqueParams();
  p.vsm.storage = shaders::kStorageFloat32;
  p.lvsm.storage = shaders::kStorageFloat32;
  p.csm.storage = shaders::kStorageFloat32;
  p.msm.storage = shaders::kStorageFloat32;
  p.msm.momentBias = 3e-6f;
  p.powerCdf.depthBias = 0.0f;
  return p;
}

}  // namespace penumbra::testing
