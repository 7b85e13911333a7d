// Lloyd relaxation of layer splits.
#include "penumbra/layer_placement.h"

#include "penumbra/shared/layer_placement.h"

namespace penumbra {
namespace {

// The sums as the shared update reads them: each fp64 total rounded to fp32, as the GPU holds
// its totals (the update divides in fp32 on both sides).
shaders::LloydStepSums stepSums(const LloydSums& sums) {
  shaders::LloydStepSums out{};
  for (size_t k = 0; k < sums.clusterWeight.size(); ++k) {
    out.clusterWeight[k] = float(sums.clusterWeight[k]);
    out.clusterSum[k] = float(sums.clusterSum[k]);
  }
  for (size_t l = 0; l < sums.layerWeight.size(); ++l) {
    out.layerWeight[l] = float(sums.layerWeight[l]);
    out.layerSum[l] = float(sums.layerSum[l]);
  }
  return out;
}

}  // namespace

std::vector<SplitSample> secondOccluderSamples(const Image& depth) {
  std::vector<SplitSample> samples;
  samples.reserve(size_t(std::max(0, depth.width() - 1)) * size_t(std::max(0, depth.height() - 1)));
  for (int y = 0; y + 1 < depth.height(); ++y) {
    for (int x = 0; x + 1 < depth.width(); ++x) {
      const shaders::SecondOccluderSample s = shaders::secondOccluderSample(
          {depth.at(x, y), depth.at(x + 1, y), depth.at(x, y + 1), depth.at(x + 1, y + 1)});
      samples.push_back({s.depth, s.weight});
    }
  }
  return samples;
}

LloydSums accumulateLloyd(std::span<const SplitSample> samples,
                          const shaders::LayerSplits& splits) {
  LloydSums sums(splits.layerCount);
  for (const SplitSample& sample : samples) {
    if (sample.weight <= 0.0f || splits.layerCount < 2) continue;
    const size_t k = size_t(shaders::nearestSplit(splits, sample.depth));
    sums.clusterWeight[k] += sample.weight;
    sums.clusterSum[k] += double(sample.weight) * sample.depth;
    const size_t layer = size_t(shaders::selectLayer(sample.depth, splits));
    sums.layerWeight[layer] += sample.weight;
    sums.layerSum[layer] += double(sample.weight) * sample.depth;
  }
  return sums;
}

shaders::LayerSplits lloydUpdate(const LloydSums& sums, const shaders::LayerSplits& splits,
                                 float minGap) {
  return shaders::lloydUpdate(stepSums(sums), splits, minGap);
}

shaders::LayerSplits lloydStep(std::span<const SplitSample> samples,
                               const shaders::LayerSplits& splits, float minGap) {
  return lloydUpdate(accumulateLloyd(samples, splits), splits, minGap);
}

shaders::LayerSplits lloydRelaxation(std::span<const SplitSample> samples, int layerCount,
                                     int iterations, float minGap, float frontMargin) {
  shaders::LayerSplits splits = shaders::uniformLayerSplits(layerCount);
  for (int i = 0; i < iterations; ++i) {
    const shaders::LayerSplits next = lloydStep(samples, splits, minGap);
    const float moved = shaders::largestSplitMove(next, splits);
    splits = next;
    if (moved < shaders::kLloydSettled) break;
  }
  return shaders::lloydPlacedSplits(splits, frontMargin, minGap);
}

}  // namespace penumbra
