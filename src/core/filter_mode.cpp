// Filter-mode names.
#include "penumbra/filter_mode.h"

#include <array>
#include <utility>

#include "penumbra/error.h"
#include "penumbra/shared/lookup_footprint.h"

namespace penumbra {
namespace {

static_assert(int(FilterMode::Point) == shaders::kFilterPoint);
static_assert(int(FilterMode::Bilinear) == shaders::kFilterBilinear);
static_assert(int(FilterMode::Trilinear) == shaders::kFilterTrilinear);
static_assert(int(FilterMode::Anisotropic) == shaders::kFilterAnisotropic);
static_assert(int(FilterMode::SummedArea) == shaders::kFilterSummedArea);
static_assert(int(FilterMode::AnisotropicDriver) == shaders::kFilterAnisotropicDriver);

constexpr std::array<std::pair<FilterMode, std::string_view>, 6> kFilterModes{{
    {FilterMode::Point, "point"},
    {FilterMode::Bilinear, "bilinear"},
    {FilterMode::Trilinear, "trilinear"},
    {FilterMode::Anisotropic, "anisotropic"},
    {FilterMode::SummedArea, "sat"},
    {FilterMode::AnisotropicDriver, "anisotropic-driver"},
}};

}  // namespace

std::string_view filterModeName(FilterMode mode) {
  for (const auto& [m, name] : kFilterModes) {
    if (m == mode) return name;
  }
  return "unknown";
}

std::string filterModeNameList() {
  std::string list;
  for (const auto& [m, name] : kFilterModes) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

FilterMode parseFilterMode(std::string_view name) {
  for (const auto& [m, n] : kFilterModes) {
    if (n == name) return m;
  }
  throw Error("unknown filter '" + std::string(name) + "'; valid filters: " + filterModeNameList());
}

bool usesMips(FilterMode mode) {
  return mode == FilterMode::Trilinear || mode == FilterMode::Anisotropic ||
         mode == FilterMode::AnisotropicDriver;
}

}  // namespace penumbra
