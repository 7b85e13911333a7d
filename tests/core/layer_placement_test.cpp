// Lloyd relaxation of LVSM splits (thesis §4.1.2): second-occluder samples, weighted k-means,
// teleportation of empty splits, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "penumbra/layer_placement.h"
#include "penumbra/shared/layer_placement.h"

namespace penumbra {
namespace {

TEST(LayerPlacement, SecondOccluderIsTheFartherDepthOfAnEvenSplit) {
  // A 2x2 block half at 0.2, half at 0.6: mu + sigma is the farther depth (thesis §4.1.2).
  Image depth(2, 2, 1);
  depth.at(0, 0) = depth.at(0, 1) = 0.2f;
  depth.at(1, 0) = depth.at(1, 1) = 0.6f;
  const auto samples = secondOccluderSamples(depth);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_NEAR(samples[0].depth, 0.6f, 1e-6f);
  EXPECT_NEAR(samples[0].weight, 0.04f, 1e-6f);  // variance (0.4/2)^2
}

TEST(LayerPlacement, FlatFootprintsCarryNoWeight) {
  const Image flat(8, 8, 1, 0.4f);
  for (const SplitSample& s : secondOccluderSamples(flat)) EXPECT_EQ(s.weight, 0.0f);
}

TEST(LayerPlacement, SplitsMoveToTheWeightedMeansOfTheirClusters) {
  std::vector<SplitSample> samples;
  for (int i = 0; i < 50; ++i) samples.push_back({0.3f + 0.001f * float(i % 5), 1.0f});
  for (int i = 0; i < 50; ++i) samples.push_back({0.8f, 2.0f});
  const shaders::LayerSplits splits = lloydRelaxation(samples, 3, 32, 1e-3f);
  EXPECT_NEAR(shaders::layerSplit(splits, 1), 0.302f, 1e-4f);
  EXPECT_NEAR(shaders::layerSplit(splits, 2), 0.8f, 1e-4f);
}

TEST(LayerPlacement, EmptySplitsAreTeleportedIntoTheHeaviestLayer) {
  // Uniform 4 layers: splits 0.25, 0.5, 0.75. All weight lies near 0.9, split by a gap.
  std::vector<SplitSample> samples;
  for (int i = 0; i < 20; ++i) samples.push_back({0.86f, 1.0f});
  for (int i = 0; i < 20; ++i) samples.push_back({0.94f, 1.0f});
  const shaders::LayerSplits step = lloydStep(samples, shaders::uniformLayerSplits(4), 1e-3f);
  // Split 0.75 takes the whole cluster (mean 0.9); 0.25 and 0.5 are empty and teleport into the
  // heaviest layer, the one above 0.75: no split is left where there is no weight.
  int above = 0;
  for (int i = 1; i < 4; ++i) above += shaders::layerSplit(step, i) > 0.8f;
  EXPECT_GE(above, 2);
  const shaders::LayerSplits relaxed = lloydRelaxation(samples, 3, 32, 1e-3f);
  EXPECT_NEAR(shaders::layerSplit(relaxed, 1), 0.86f, 1e-3f);
  EXPECT_NEAR(shaders::layerSplit(relaxed, 2), 0.94f, 1e-3f);
}

TEST(LayerPlacement, SplitsStayIncreasingApartAndInsideTheUnitInterval) {
  std::vector<SplitSample> samples(30, SplitSample{0.999f, 1.0f});
  const shaders::LayerSplits splits = lloydRelaxation(samples, 5, 16, 0.01f);
  float previous = 0.0f;
  for (int i = 1; i < 5; ++i) {
    const float s = shaders::layerSplit(splits, i);
    EXPECT_GE(s - previous, 0.01f - 1e-6f);
    EXPECT_LT(s, 1.0f);
    previous = s;
  }
}

TEST(LayerPlacement, IsDeterministic) {
  std::vector<SplitSample> samples;
  for (int i = 0; i < 200; ++i)
    samples.push_back({std::fmod(0.37f * float(i), 1.0f), float(i % 7)});
  const shaders::LayerSplits a = lloydRelaxation(samples, 6, 16, 1e-3f);
  const shaders::LayerSplits b = lloydRelaxation(samples, 6, 16, 1e-3f);
  for (int i = 1; i < 6; ++i) EXPECT_EQ(shaders::layerSplit(a, i), shaders::layerSplit(b, i));
}

// The packing as a list would do it: a stable sort, pushed forward from 0, then back from 1.
std::vector<float> packedAsAList(std::vector<float> splits, float minGap) {
  std::stable_sort(splits.begin(), splits.end());
  float previous = 0.0f;
  for (float& s : splits) previous = s = std::max(s, previous + minGap);
  float next = 1.0f;
  for (auto s = splits.rbegin(); s != splits.rend(); ++s) next = *s = std::min(*s, next - minGap);
  return splits;
}

shaders::LayerSplits splitsOf(const std::vector<float>& interior) {
  shaders::LayerSplits s = shaders::uniformLayerSplits(int(interior.size()) + 1);
  for (size_t k = 0; k < interior.size(); ++k) s.interior[k / 4][k % 4] = interior[k];
  return s;
}

std::vector<float> interiorOf(const shaders::LayerSplits& s) {
  std::vector<float> interior;
  for (int i = 1; i < s.layerCount; ++i) interior.push_back(shaders::layerSplit(s, i));
  return interior;
}

// The shared packing ranks the splits and indexes its arrays with loop constants only (with
// run-time indexes llvmpipe took seconds to compile the Lloyd step): it must give what a sorted
// list gives, from one layer (no split) to all 16, ties included; so must the placement, which
// moves each split toward the light first. Draws from a few values make ties common; the
// arithmetic is the same subtraction, max and min in the same order, so the results agree to
// the bit.
TEST(LayerPlacement, PackingAndPlacementAreASortedListSpacedApart) {
  std::mt19937 random(7);
  const float values[] = {0.0f, 0.1f, 0.1f, 0.3f, 0.5f, 0.5f, 0.52f, 0.9f, 0.995f, 1.0f};
  for (int trial = 0; trial < 400; ++trial) {
    const int layers = 1 + int(random() % shaders::kMaxLayers);
    std::vector<float> interior(size_t(layers - 1));
    for (float& v : interior) v = values[random() % std::size(values)];
    const float minGap = trial % 2 ? 0.001f : 0.02f;
    EXPECT_EQ(interiorOf(shaders::packSplits(splitsOf(interior), minGap)),
              packedAsAList(interior, minGap))
        << "trial " << trial << ", " << layers << " layers";
    const float margin = 0.01f;
    std::vector<float> moved = interior;
    for (float& v : moved) v -= margin;
    EXPECT_EQ(interiorOf(shaders::lloydPlacedSplits(splitsOf(interior), margin, minGap)),
              packedAsAList(moved, minGap))
        << "trial " << trial << ", " << layers << " layers";
  }
}

// The shared update keeps each weighted cluster's mean and teleports the empty ones in cluster
// order, each into the heaviest layer left or, with none, to the old split of its turn. As a list
// would do it: the kept means, then the teleports, packed. The old splits are spaced unevenly,
// so that a teleport that kept another place than its turn's would show.
TEST(LayerPlacement, UpdateIsTheKeptMeansAndTeleportsOfAList) {
  std::mt19937 random(11);
  for (int trial = 0; trial < 400; ++trial) {
    const int layers = 2 + int(random() % (shaders::kMaxLayers - 1));
    const int n = layers - 1;
    std::vector<float> old(static_cast<size_t>(n));
    for (float& v : old) v = float(1 + random() % 998) / 1000.0f;
    const shaders::LayerSplits splits = splitsOf(packedAsAList(old, 0.001f));
    shaders::LloydStepSums sums{};
    for (int k = 0; k < n; ++k) {
      // Two in five clusters empty; a mean inside (0,1).
      sums.clusterWeight[k] = random() % 5 < 2 ? 0.0f : float(1 + random() % 9);
      sums.clusterSum[k] = sums.clusterWeight[k] * float(random() % 1000) / 1000.0f;
    }
    for (int l = 0; l < layers; ++l) {
      // Layers weigh nothing in one trial in three, else some of them do, ties included.
      sums.layerWeight[l] = trial % 3 == 0 || random() % 3 == 0 ? 0.0f : float(1 + random() % 4);
      sums.layerSum[l] = sums.layerWeight[l] * float(random() % 1000) / 1000.0f;
    }
    std::vector<float> list;
    for (int k = 0; k < n; ++k) {
      if (sums.clusterWeight[k] > 0.0f) list.push_back(sums.clusterSum[k] / sums.clusterWeight[k]);
    }
    std::vector<float> layerWeight(sums.layerWeight, sums.layerWeight + layers);
    for (int turn = 0; list.size() < size_t(n); ++turn) {
      const size_t heaviest = size_t(std::max_element(layerWeight.begin(), layerWeight.end()) -
                                     layerWeight.begin());  // the first of equals
      if (layerWeight[heaviest] > 0.0f) {
        list.push_back(sums.layerSum[heaviest] / layerWeight[heaviest]);
        layerWeight[heaviest] = 0.0f;
      } else {
        list.push_back(shaders::layerSplit(splits, turn + 1));
      }
    }
    const std::vector<float> expected = packedAsAList(list, 0.001f);
    EXPECT_EQ(interiorOf(shaders::lloydUpdate(sums, splits, 0.001f)), expected)
        << "trial " << trial << ", " << layers << " layers";
  }
}

}  // namespace
}  // namespace penumbra
