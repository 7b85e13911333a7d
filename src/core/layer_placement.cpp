// Lloyd relaxation of layer splits.
#include "penumbra/layer_placement.h"

#include <algorithm>
#include <cmath>

#include "penumbra/shared/layer_placement.h"

namespace penumbra {
namespace {

std::vector<float> interior(const shaders::LayerSplits& splits) {
  std::vector<float> s;
  for (int i = 1; i < splits.layerCount; ++i) s.push_back(shaders::layerSplit(splits, i));
  return s;
}

shaders::LayerSplits pack(std::vector<float> s, int layerCount, float minGap) {
  std::sort(s.begin(), s.end());
  // Keep the splits strictly inside (0,1) and apart, pushing forward then back.
  for (size_t i = 0; i < s.size(); ++i) {
    const float lowest = (i == 0 ? 0.0f : s[i - 1]) + minGap;
    s[i] = std::max(s[i], lowest);
  }
  for (size_t i = s.size(); i-- > 0;) {
    const float highest = (i + 1 == s.size() ? 1.0f : s[i + 1]) - minGap;
    s[i] = std::min(s[i], highest);
  }
  shaders::LayerSplits out = shaders::uniformLayerSplits(layerCount);
  for (size_t k = 0; k < s.size(); ++k) out.interior[k / 4][k % 4] = s[k];
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
  const std::vector<float> s = interior(splits);
  if (s.empty()) return splits;
  std::vector<double> layerWeight = sums.layerWeight;
  std::vector<float> next;
  int empty = 0;
  for (size_t k = 0; k < s.size(); ++k) {
    if (sums.clusterWeight[k] > 0.0) {
      next.push_back(float(sums.clusterSum[k] / sums.clusterWeight[k]));
    } else {
      ++empty;
    }
  }
  // Teleportation: each empty cluster's split reappears inside the heaviest remaining layer.
  for (int i = 0; i < empty; ++i) {
    const size_t heaviest =
        size_t(std::max_element(layerWeight.begin(), layerWeight.end()) - layerWeight.begin());
    if (layerWeight[heaviest] > 0.0) {
      next.push_back(float(sums.layerSum[heaviest] / layerWeight[heaviest]));
      layerWeight[heaviest] = 0.0;  // the next teleport goes elsewhere
    } else {
      next.push_back(s[size_t(i) % s.size()]);  // no weight anywhere: keep the split
    }
  }
  return pack(next, splits.layerCount, minGap);
}

shaders::LayerSplits lloydStep(std::span<const SplitSample> samples,
                               const shaders::LayerSplits& splits, float minGap) {
  return lloydUpdate(accumulateLloyd(samples, splits), splits, minGap);
}

shaders::LayerSplits lloydRelaxation(int layerCount, int iterations, float minGap,
                                     float frontMargin, const LloydAccumulator& accumulate) {
  shaders::LayerSplits splits = shaders::uniformLayerSplits(layerCount);
  for (int i = 0; i < iterations; ++i) {
    const shaders::LayerSplits next = lloydUpdate(accumulate(splits), splits, minGap);
    float moved = 0.0f;
    for (int k = 1; k < layerCount; ++k) {
      moved =
          std::max(moved, std::abs(shaders::layerSplit(next, k) - shaders::layerSplit(splits, k)));
    }
    splits = next;
    if (moved < 1e-6f) break;
  }
  std::vector<float> placed = interior(splits);
  for (float& s : placed) s -= frontMargin;
  return pack(placed, layerCount, minGap);
}

shaders::LayerSplits lloydRelaxation(std::span<const SplitSample> samples, int layerCount,
                                     int iterations, float minGap, float frontMargin) {
  return lloydRelaxation(
      layerCount, iterations, minGap, frontMargin,
      [&](const shaders::LayerSplits& splits) { return accumulateLloyd(samples, splits); });
}

}  // namespace penumbra
