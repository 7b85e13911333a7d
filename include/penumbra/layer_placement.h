// Layer split placement for layered VSM by Lloyd relaxation (thesis §4.1.2): light bleeding comes
// from depth discontinuities, so the splits are the centres of a 1D weighted k-means over each
// filter footprint's "second occluder" depth mu + sigma, weighted by its variance sigma^2.
#pragma once

#include <algorithm>
#include <span>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/shared/layer_placement.h"

namespace penumbra {

struct SplitSample {
  float depth;   // mu + sigma of a 2x2 footprint: the farther depth when two depths share it
  float weight;  // sigma^2, zero for flat footprints
};

// One sample per 2x2 texel block between texel centres of the unwarped moments (z, z^2) of a
// linear depth map: (w-1) x (h-1) samples, row-major. Blocks touching empty texels (depth 1, the
// cleared far plane) weigh nothing: an edge against nothing is no occluder.
std::vector<SplitSample> secondOccluderSamples(const Image& depth);

// What a Lloyd step gathers from the samples: per split (cluster) and per layer, the total
// weight and the weighted sum of depths.
struct LloydSums {
  explicit LloydSums(int layerCount)
      : clusterWeight(size_t(std::max(layerCount - 1, 0)), 0.0),
        clusterSum(size_t(std::max(layerCount - 1, 0)), 0.0),
        layerWeight(size_t(layerCount), 0.0),
        layerSum(size_t(layerCount), 0.0) {}
  std::vector<double> clusterWeight, clusterSum;
  std::vector<double> layerWeight, layerSum;
};

// Gathers the sums: each weighted sample joins its nearest split (the first of equals) and the
// layer that contains it, in fp64. The GPU gathers the same sums in fp32 (passes/lloyd_sums.comp).
LloydSums accumulateLloyd(std::span<const SplitSample> samples, const shaders::LayerSplits& splits);

// Moves each split to its cluster's weighted mean, teleports empty ones (below), keeps order.
shaders::LayerSplits lloydUpdate(const LloydSums& sums, const shaders::LayerSplits& splits,
                                 float minGap);

// One Lloyd step: each sample joins its nearest split, each split moves to its samples' weighted
// mean. A split left with no weight is teleported (thesis: "merge the two adjacent layers and
// split whatever layer has the highest weight"): removed, and a split placed at the weighted
// mean of the heaviest layer. Splits stay increasing, at least `minGap` apart and from 0 and 1.
shaders::LayerSplits lloydStep(std::span<const SplitSample> samples,
                               const shaders::LayerSplits& splits, float minGap);

// Uniform splits relaxed for up to `iterations` steps, stopping early once no split moves by
// more than shaders::kLloydSettled, then moved `frontMargin` toward the light. Deterministic for a
// given input. The relaxed centres sit at second occluders' mean depths; a boundary exactly there
// would leave half of those surfaces in the layer in front, still bleeding, so the renderer places
// each split one overlap in front of its centre.
shaders::LayerSplits lloydRelaxation(std::span<const SplitSample> samples, int layerCount,
                                     int iterations, float minGap, float frontMargin = 0.0f);

}  // namespace penumbra
