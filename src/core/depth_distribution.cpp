// Techniques evaluated exactly on a weighted depth distribution (one filter region).
#include "penumbra/depth_distribution.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>

#include "penumbra/error.h"
#include "penumbra/storage_format.h"
#include "penumbra/shared/channel_reduction.h"

namespace penumbra {
namespace {

float parseFloat(std::string_view text, std::string_view what, size_t index) {
  float value = 0.0f;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
    throw Error("depth distribution item " + std::to_string(index + 1) + ": " + std::string(what) +
                " '" + std::string(text) + "' is not a number");
  }
  return value;
}

float totalWeight(const std::vector<DepthSample>& region) {
  float sum = 0.0f;
  for (const DepthSample& s : region) sum += s.weight;
  return sum;
}

}  // namespace

std::vector<DepthSample> parseDepthDistribution(std::string_view text) {
  std::vector<DepthSample> samples;
  if (text.empty()) throw Error("depth distribution is empty; expected DEPTH:WEIGHT,...");
  size_t start = 0;
  while (true) {
    size_t comma = text.find(',', start);
    std::string_view item =
        text.substr(start, comma == std::string_view::npos ? text.npos : comma - start);
    size_t index = samples.size();
    size_t colon = item.find(':');
    if (colon == std::string_view::npos) {
      throw Error("depth distribution item " + std::to_string(index + 1) + " '" +
                  std::string(item) + "' must be DEPTH:WEIGHT");
    }
    DepthSample s{parseFloat(item.substr(0, colon), "depth", index),
                  parseFloat(item.substr(colon + 1), "weight", index)};
    if (s.depth < 0.0f || s.depth > 1.0f) {
      throw Error("depth distribution item " + std::to_string(index + 1) + ": depth " +
                  std::string(item.substr(0, colon)) + " is out of range [0, 1]");
    }
    if (!(s.weight > 0.0f) || s.weight > 1.0f) {
      throw Error("depth distribution item " + std::to_string(index + 1) + ": weight " +
                  std::string(item.substr(colon + 1)) + " is out of range (0, 1]");
    }
    samples.push_back(s);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  const float sum = totalWeight(samples);
  if (sum > 1.0f + 1e-5f) {
    throw Error("depth distribution weights sum to " + std::to_string(sum) +
                ", more than the whole filter region (1)");
  }
  return samples;
}

std::vector<DepthSample> regionWithReceiver(const std::vector<DepthSample>& occluders,
                                            float receiverDepth) {
  std::vector<DepthSample> region(occluders.begin(), occluders.end());
  const float rest = 1.0f - totalWeight(occluders);
  if (rest > 1e-6f) region.push_back({receiverDepth, rest});
  return region;
}

float exactVisibility(const std::vector<DepthSample>& region, float receiverDepth) {
  float lit = 0.0f;
  for (const DepthSample& s : region) {
    if (s.depth >= receiverDepth) lit += s.weight;
  }
  return lit / totalWeight(region);
}

std::vector<float> filterRegion(Technique technique, const TechniqueParams& params,
                                const std::vector<DepthSample>& region) {
  const int count = channelCount(technique, params);
  const StorageFormat storage = techniqueStorage(technique, params);
  const float total = totalWeight(region);
  std::vector<std::vector<float>> encoded;
  for (const DepthSample& s : region) {
    std::vector<float> channels(size_t(count), 0.0f);
    encodeDepth(technique, params, s.depth, channels);
    for (float& v : channels) v = quantizeToStorage(v, storage);
    encoded.push_back(std::move(channels));
  }
  std::vector<float> filtered(size_t(count), 0.0f);
  for (int c = 0; c < count; ++c) {
    auto acc = shaders::startReduction(int(channelReduction(technique, params, c)),
                                       params.esm.exponent);
    for (size_t i = 0; i < region.size(); ++i) {
      acc = shaders::accumulateTap(acc, encoded[i][size_t(c)], region[i].weight / total);
    }
    filtered[size_t(c)] = quantizeToStorage(shaders::reductionResult(acc), storage);
  }
  return filtered;
}

float evaluateOnRegion(Technique technique, const TechniqueParams& params,
                       const std::vector<DepthSample>& region, float receiverDepth) {
  if (filtersAfterTest(technique)) {
    float visibility = 0.0f;
    for (const DepthSample& s : region) {
      const float depth[1] = {s.depth};
      visibility += s.weight * reconstructVisibility(technique, params, depth, receiverDepth);
    }
    return visibility / totalWeight(region);
  }
  return reconstructVisibility(technique, params, filterRegion(technique, params, region),
                               receiverDepth);
}

}  // namespace penumbra
