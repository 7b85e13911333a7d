// The closed set of shadow-map techniques, their ids, and the CPU reference of their math:
// encode a depth into channels, say how each channel is filtered, reconstruct visibility.
// Every formula lives in src/shaders/shared/ and is compiled here as C++ (see
// technique_dispatch.h).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "penumbra/shared/technique_params.h"

namespace penumbra {

struct Scene;

enum class Technique { Hard, Pcf, Vsm, Lvsm, Evsm2, Evsm4, Esm, Csm, PowerCdf, Msm };

// Channel reductions for filtering, mirroring the shared kReduce* constants.
enum class ChannelReduction { Mean, Min, Max, LogMeanExp };

using TechniqueParams = shaders::TechniqueParams;

// All techniques, in the order reports list them.
std::span<const Technique> allTechniques();

// Throws Error for a value outside the enumeration (an integer cast to Technique, e.g. from a
// stored id); every function here and in params.h checks its technique this way.
void checkTechnique(Technique technique);

// The id used on the command line, in JSON, CSV and file names: "hard", "pcf", "vsm", "lvsm",
// "evsm2", "evsm4", "esm", "csm", "powercdf", "msm".
std::string_view techniqueId(Technique technique);
// A human-readable name with its source, e.g. "Variance shadow maps (thesis ch. 3)".
std::string_view techniqueTitle(Technique technique);
// Parses an id; throws Error naming the valid ids when it is unknown.
Technique parseTechnique(std::string_view id);
// The valid ids joined by ", ".
std::string techniqueIdList();

// The papers' defaults for every technique.
TechniqueParams defaultTechniqueParams();

int channelCount(Technique technique, const TechniqueParams& params);
// Encodes a linear light-space depth in [0,1] into channelCount() values.
void encodeDepth(Technique technique, const TechniqueParams& params, float depth,
                 std::span<float> channels);
ChannelReduction channelReduction(Technique technique, const TechniqueParams& params, int channel);
// Visibility in [0,1] from filtered channels (channelCount() values) for a receiver depth.
float reconstructVisibility(Technique technique, const TechniqueParams& params,
                            std::span<const float> filteredChannels, float receiverDepth);
// PCF filters the test results, not the channels.
bool filtersAfterTest(Technique technique);
// Whether a translucent (BLEND) caster's shadow keeps its 1 - alpha through the technique: the
// light pass covers a dithered alpha share of the texels (shared/alpha_mask.h) and filtering
// averages the dither. Not the hard test (no filter: the dither would show), EVSM2 (its positive
// warp alone over-lights the mixture: 0.82 for 0.75) nor the power-function CDF (0.11 for 0.75),
// measured by SceneRenderingTest.ATranslucentCardLetsThroughOneMinusAlpha: their light pass
// draws translucent casters as a mask at alpha 0.5.
bool carriesTranslucency(Technique technique);
// For a scene with translucent casters: a warning naming those of `techniques` that cannot carry
// them (carriesTranslucency); empty otherwise.
std::string translucencyWarning(const Scene& scene, std::span<const Technique> techniques);
// Whether the technique encodes depth into channels that are filtered before the test (blur,
// mips, summed-area table): every technique but PCF (which filters after the test) and the hard
// test (which does not filter). The one answer to "does it prefilter" for the GPU passes, the
// CPU twin and the front ends.
bool prefiltersChannels(Technique technique);
// Why the summed-area filter cannot hold this technique's channels, or nothing where it can: it
// averages (no min/max or log-space reductions) in fixed point relative to the channels' range
// (exponential channels span too many orders of magnitude). Techniques that do not prefilter
// pass.
std::optional<std::string> summedAreaRefusal(Technique technique, const TechniqueParams& params);
// Throws Error with summedAreaRefusal's reason.
void checkSummedAreaFilterable(Technique technique, const TechniqueParams& params);

}  // namespace penumbra
