// A depth distribution inside one filter region, and every technique evaluated on it exactly:
// the filtered channels are the weighted reductions of the encoded depths, as an ideal prefilter
// over that region would produce. This is how the papers plot their shadow tests.
#pragma once

#include <string_view>
#include <vector>

#include "penumbra/technique.h"

namespace penumbra {

struct DepthSample {
  float depth;   // linear light-space depth in [0,1]
  float weight;  // share of the filter region, (0,1]
};

// Parses "DEPTH:WEIGHT,DEPTH:WEIGHT,..." (e.g. "0.3:0.5,0.5:0.5"). Depths in [0,1], weights in
// (0,1] summing to at most 1; throws Error naming the offending item otherwise.
std::vector<DepthSample> parseDepthDistribution(std::string_view text);

// The occluders plus the planar receiver itself: weight 1 - sum(w) at the receiver's depth.
std::vector<DepthSample> regionWithReceiver(const std::vector<DepthSample>& occluders,
                                            float receiverDepth);

// The exact filtered shadow test: the weight of samples at or behind the receiver.
float exactVisibility(const std::vector<DepthSample>& region, float receiverDepth);

// The technique's filtered channels over the region (weights normalised to sum 1).
std::vector<float> filterRegion(Technique technique, const TechniqueParams& params,
                                const std::vector<DepthSample>& region);

// The technique's visibility for a receiver over the region: PCF tests then filters; the others
// filter their channels then reconstruct.
float evaluateOnRegion(Technique technique, const TechniqueParams& params,
                       const std::vector<DepthSample>& region, float receiverDepth);

}  // namespace penumbra
