// Depth distributions: parsing with clear errors, the exact filtered step, region filtering.
#include <gtest/gtest.h>

#include "penumbra/depth_distribution.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

std::string errorOf(std::string_view text) {
  try {
    parseDepthDistribution(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(DepthDistribution, ParsesDepthWeightPairs) {
  const auto samples = parseDepthDistribution("0.3:0.5,0.5:0.25");
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_FLOAT_EQ(samples[0].depth, 0.3f);
  EXPECT_FLOAT_EQ(samples[1].weight, 0.25f);
}

TEST(DepthDistribution, MalformedInputNamesTheItem) {
  EXPECT_NE(errorOf("").find("empty"), std::string::npos);
  EXPECT_NE(errorOf("0.3").find("item 1 '0.3' must be DEPTH:WEIGHT"), std::string::npos);
  EXPECT_NE(errorOf("0.3:0.5,x:0.2").find("item 2: depth 'x' is not a number"), std::string::npos);
  EXPECT_NE(errorOf("1.3:0.5").find("out of range [0, 1]"), std::string::npos);
  EXPECT_NE(errorOf("0.3:0").find("weight 0 is out of range (0, 1]"), std::string::npos);
  EXPECT_NE(errorOf("0.3:0.7,0.4:0.7").find("sum to"), std::string::npos);
  EXPECT_NE(errorOf("0.3:0.5,").find("item 2"), std::string::npos);
}

TEST(DepthDistribution, ReceiverFillsTheRestOfTheRegion) {
  const auto region = regionWithReceiver({{0.3f, 0.25f}}, 0.6f);
  ASSERT_EQ(region.size(), 2u);
  EXPECT_FLOAT_EQ(region[1].depth, 0.6f);
  EXPECT_FLOAT_EQ(region[1].weight, 0.75f);
  EXPECT_FLOAT_EQ(exactVisibility(region, 0.6f), 0.75f);
  EXPECT_FLOAT_EQ(exactVisibility(region, 0.2f), 1.0f);
}

TEST(DepthDistribution, FilteringAveragesEncodedChannels) {
  const TechniqueParams params = defaultTechniqueParams();
  const auto moments = filterRegion(Technique::Vsm, params, {{0.2f, 0.5f}, {0.6f, 0.5f}});
  EXPECT_FLOAT_EQ(moments[0], 0.4f);
  EXPECT_FLOAT_EQ(moments[1], 0.5f * (0.04f + 0.36f));
  const auto minMaxMean = filterRegion(Technique::PowerCdf, params, {{0.2f, 0.25f}, {0.6f, 0.75f}});
  EXPECT_FLOAT_EQ(minMaxMean[0], 0.2f);
  EXPECT_FLOAT_EQ(minMaxMean[1], 0.6f);
  EXPECT_FLOAT_EQ(minMaxMean[2], 0.5f);
}

}  // namespace
}  // namespace penumbra
