// How the camera pass reads the prefiltered shadow map (docs/renderer.md,
// shared/lookup_footprint.h).
#pragma once

#include <string>
#include <string_view>

namespace penumbra {

// In the order of shared/lookup_footprint.h kFilter*. Anisotropic filters every channel through
// the probes the filtered reference models, so every technique is ranked under one kernel;
// AnisotropicDriver gives mean channels the driver's anisotropic filter (its own kernel: the
// techniques whose channels are all mean then differ from the reference by more).
enum class FilterMode { Point, Bilinear, Trilinear, Anisotropic, SummedArea, AnisotropicDriver };

// "point", "bilinear", "trilinear", "anisotropic", "sat", "anisotropic-driver"
std::string_view filterModeName(FilterMode mode);
// Throws Error listing the valid names.
FilterMode parseFilterMode(std::string_view name);
std::string filterModeNameList();
// Trilinear and anisotropic lookups read a mip chain.
bool usesMips(FilterMode mode);

}  // namespace penumbra
