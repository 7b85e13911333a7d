// How the camera pass reads the prefiltered shadow map (docs/renderer.md,
// shared/lookup_footprint.h).
#pragma once

#include <string>
#include <string_view>

namespace penumbra {

// In the order of shared/lookup_footprint.h kFilter*.
enum class FilterMode { Point, Bilinear, Trilinear, Anisotropic, SummedArea };

std::string_view filterModeName(FilterMode mode);  // "point", "bilinear", ..., "sat"
// Throws Error listing the valid names.
FilterMode parseFilterMode(std::string_view name);
std::string filterModeNameList();
// Trilinear and anisotropic lookups read a mip chain.
bool usesMips(FilterMode mode);

}  // namespace penumbra
