// Lloyd relaxation of LVSM splits (thesis §4.1.2): second-occluder samples, weighted k-means,
// teleportation of empty splits, determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "penumbra/layer_placement.h"

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

}  // namespace
}  // namespace penumbra
