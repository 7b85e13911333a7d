// Technique ids and the C++ side of the shared dispatcher
// (src/shaders/shared/technique_dispatch.h).
#include "penumbra/technique.h"

#include "penumbra/scene.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <optional>
#include <type_traits>

#include "penumbra/error.h"
#include "penumbra/shared/technique_dispatch.h"

namespace penumbra {
namespace {

struct TechniqueInfo {
  Technique technique;
  int sharedId;
  std::string_view id;
  std::string_view title;
};

constexpr std::array<TechniqueInfo, 10> kTechniques{{
    {Technique::Hard, shaders::kTechniqueHard, "hard", "Hard shadow map test with bias"},
    {Technique::Pcf, shaders::kTechniquePcf, "pcf", "Percentage-closer filtering (thesis ch. 2)"},
    {Technique::Vsm, shaders::kTechniqueVsm, "vsm", "Variance shadow maps (thesis ch. 3)"},
    {Technique::Lvsm, shaders::kTechniqueLvsm, "lvsm", "Layered variance shadow maps (thesis 4.1)"},
    {Technique::Evsm2, shaders::kTechniqueEvsm2, "evsm2",
     "Exponential VSM, positive warp (thesis 4.2)"},
    {Technique::Evsm4, shaders::kTechniqueEvsm4, "evsm4",
     "Exponential VSM, positive and negative warps (thesis 4.2)"},
    {Technique::Esm, shaders::kTechniqueEsm, "esm", "Exponential shadow maps (Annen et al. 2008)"},
    {Technique::Csm, shaders::kTechniqueCsm, "csm", "Convolution shadow maps (Annen et al. 2007)"},
    {Technique::PowerCdf, shaders::kTechniquePowerCdf, "powercdf",
     "Power-function CDF (Gumbau et al. 2011)"},
    {Technique::Msm, shaders::kTechniqueMsm, "msm",
     "Moment shadow maps, Hamburger 4MSM (Peters & Klein 2015)"},
}};

constexpr std::array<Technique, shaders::kTechniqueCount> kAll{
    Technique::Hard,  Technique::Pcf, Technique::Vsm, Technique::Lvsm,     Technique::Evsm2,
    Technique::Evsm4, Technique::Esm, Technique::Csm, Technique::PowerCdf, Technique::Msm};

// Every id in [0, kTechniqueCount) once: a technique left out of kAll (its missing entries would
// read as Hard) would drop out of every "all techniques" test and of the accuracy gate.
constexpr bool listsEveryTechniqueOnce(const std::array<Technique, shaders::kTechniqueCount>& all) {
  for (int id = 0; id < shaders::kTechniqueCount; ++id) {
    int seen = 0;
    for (Technique t : all) seen += int(t) == id;
    if (seen != 1) return false;
  }
  return true;
}
static_assert(listsEveryTechniqueOnce(kAll));

const TechniqueInfo& info(Technique technique) {
  checkTechnique(technique);
  const TechniqueInfo& i = kTechniques[static_cast<size_t>(technique)];
  assert(i.technique == technique);
  return i;
}

int sharedId(Technique technique) {
  return info(technique).sharedId;
}

static_assert(kTechniques.size() == size_t(shaders::kTechniqueCount));
// info() indexes kTechniques by the enum's value, and the shaders by the shared id.
constexpr bool indexedByTechnique() {
  for (size_t i = 0; i < kTechniques.size(); ++i) {
    if (size_t(kTechniques[i].technique) != i || kTechniques[i].sharedId != int(i)) return false;
  }
  return true;
}
static_assert(indexedByTechnique());
static_assert(int(ChannelReduction::Mean) == shaders::kReduceMean);
static_assert(int(ChannelReduction::Min) == shaders::kReduceMin);
static_assert(int(ChannelReduction::Max) == shaders::kReduceMax);
static_assert(int(ChannelReduction::LogMeanExp) == shaders::kReduceLogMeanExp);
// GPU-mirrored blocks keep std140/std430 layout: whole vec4 rows.
static_assert(sizeof(shaders::LayerSplits) % 16 == 0);
static_assert(sizeof(TechniqueParams) % 16 == 0);
static_assert(sizeof(shaders::TexelLayerRangeTable) == 16 * size_t(shaders::kMaxTexelLayers));

}  // namespace

std::span<const Technique> allTechniques() {
  return kAll;
}

void checkTechnique(Technique technique) {
  const auto id = static_cast<std::underlying_type_t<Technique>>(technique);
  if (id < 0 || size_t(id) >= kTechniques.size()) {
    throw Error("technique id " + std::to_string(id) + " is out of range [0, " +
                std::to_string(kTechniques.size() - 1) +
                "]; valid techniques: " + techniqueIdList());
  }
}

std::string_view techniqueId(Technique technique) {
  return info(technique).id;
}

std::string_view techniqueTitle(Technique technique) {
  return info(technique).title;
}

std::string techniqueIdList() {
  std::string list;
  for (const TechniqueInfo& i : kTechniques) {
    if (!list.empty()) list += ", ";
    list += i.id;
  }
  return list;
}

Technique parseTechnique(std::string_view id) {
  for (const TechniqueInfo& i : kTechniques) {
    if (i.id == id) return i.technique;
  }
  throw Error("unknown technique '" + std::string(id) +
              "'; valid techniques: " + techniqueIdList());
}

TechniqueParams defaultTechniqueParams() {
  return shaders::defaultTechniqueParams();
}

int channelCount(Technique technique, const TechniqueParams& params) {
  return shaders::techniqueChannelCount(sharedId(technique), params);
}

void encodeDepth(Technique technique, const TechniqueParams& params, float depth,
                 std::span<float> channels) {
  const int count = channelCount(technique, params);
  assert(int(channels.size()) >= count);
  const int id = sharedId(technique);
  shaders::TexelEncoding e = shaders::startTexelEncoding(id, depth, params);
  for (int texelLayer = 0; 4 * texelLayer < count; ++texelLayer) {
    const glm::vec4 v = shaders::encodeCurrentTexelLayer(
        id, e, shaders::texelLayerRanges(id, texelLayer, params), params);
    for (int c = 0; c < 4 && 4 * texelLayer + c < count; ++c) {
      channels[size_t(4 * texelLayer + c)] = v[c];
    }
    e = shaders::nextTexelLayer(id, e);
  }
}

ChannelReduction channelReduction(Technique technique, const TechniqueParams& params, int channel) {
  return ChannelReduction(shaders::channelReduction(sharedId(technique), channel, params));
}

float reconstructVisibility(Technique technique, const TechniqueParams& params,
                            std::span<const float> filteredChannels, float receiverDepth) {
  float channels[shaders::kMaxChannels] = {};
  const size_t count = std::min(filteredChannels.size(), size_t(shaders::kMaxChannels));
  for (size_t i = 0; i < count; ++i) channels[i] = filteredChannels[i];
  return shaders::reconstructVisibility(sharedId(technique), channels, receiverDepth, params);
}

bool filtersAfterTest(Technique technique) {
  return shaders::techniqueFiltersAfterTest(sharedId(technique));
}

bool carriesTranslucency(Technique technique) {
  return technique != Technique::Hard && technique != Technique::Evsm2 &&
         technique != Technique::PowerCdf;
}

std::string translucencyWarning(const Scene& scene, std::span<const Technique> techniques) {
  const bool translucent = std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) {
    return m.castsShadow && m.alphaMode == AlphaMode::Blend;
  });
  std::string names;
  for (Technique t : techniques) {
    if (!carriesTranslucency(t)) names += (names.empty() ? "" : ", ") + std::string(techniqueId(t));
  }
  if (!translucent || names.empty()) return {};
  return "scene '" + scene.name +
         "' has translucent (BLEND) casters, whose shadows let through "
         "1 - alpha, but " +
         names +
         " cannot carry it and draw them as a mask at alpha 0.5 (docs/techniques.md, "
         "\"Translucent casters\")";
}

bool prefiltersChannels(Technique technique) {
  return shaders::techniquePrefiltersChannels(sharedId(technique));
}

std::optional<std::string> summedAreaRefusal(Technique technique, const TechniqueParams& params) {
  if (!prefiltersChannels(technique)) return std::nullopt;
  if (technique == Technique::Evsm2 || technique == Technique::Evsm4 ||
      technique == Technique::Esm) {
    // Fixed-point sums bound the error by the channel's largest deviation (R * 2^-32):
    // exponential channels span up to e^+-84, so every small value would drown.
    return "the summed-area filter sums channels in fixed point relative to their range; " +
           std::string(techniqueId(technique)) +
           "'s exponential channels span too many orders of magnitude; use vsm, lvsm, csm or "
           "msm with sat, or trilinear/anisotropic for this technique";
  }
  for (int c = 0; c < channelCount(technique, params); ++c) {
    if (channelReduction(technique, params, c) != ChannelReduction::Mean) {
      return "the summed-area filter averages channels, but " +
             std::string(techniqueId(technique)) +
             " has min/max or log-space channels; use point, bilinear, trilinear or "
             "anisotropic";
    }
  }
  return std::nullopt;
}

void checkSummedAreaFilterable(Technique technique, const TechniqueParams& params) {
  if (std::optional<std::string> refusal = summedAreaRefusal(technique, params)) {
    throw Error(*refusal);
  }
}

}  // namespace penumbra
