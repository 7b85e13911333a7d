// The request, its work units and shards (tune.h).
#include <algorithm>
#include <charconv>
#include <cmath>

#include "penumbra/area_light.h"
#include "penumbra/error.h"
#include "penumbra/truth/true_shadow.h"
#include "penumbra/tune/tune.h"

namespace penumbra::tune {
namespace {

constexpr std::pair<ErrorMeasure, std::string_view> kMeasures[] = {
    {ErrorMeasure::Rmse, "rmse"},
    {ErrorMeasure::LeakWeighted, "leak-weighted"},
    {ErrorMeasure::Flicker, "flicker"},
};
constexpr std::pair<Target, std::string_view> kTargets[] = {
    {Target::RayTraced, "raytraced"},
    {Target::Filtered, "filtered"},
};

template <typename T, size_t N>
std::string namesOf(const std::pair<T, std::string_view> (&table)[N]) {
  std::string list;
  for (const auto& [value, name] : table) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

// A name table's name for `value`, and the value of `name` (Error listing the valid names as
// "valid <what>s").
template <typename T, size_t N>
std::string_view nameIn(const std::pair<T, std::string_view> (&table)[N], T value) {
  for (const auto& [v, name] : table) {
    if (v == value) return name;
  }
  throw Error("tune: a value outside its name table");
}

template <typename T, size_t N>
T valueIn(const std::pair<T, std::string_view> (&table)[N], std::string_view name,
          const std::string& what) {
  for (const auto& [v, n] : table) {
    if (n == name) return v;
  }
  throw Error("unknown " + what + " '" + std::string(name) + "'; valid " + what + "s: " +
              namesOf(table));
}

void requireRange(double value, double lo, double hi, const std::string& what) {
  if (!(value >= lo && value <= hi)) {
    throw Error(what + " " + std::to_string(value) + " is out of range [" + std::to_string(lo) +
                ", " + std::to_string(hi) + "]");
  }
}

int parsePositive(std::string_view text, std::string_view whole) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw Error("--shard '" + std::string(whole) + "' is not K/N with whole numbers");
  }
  return value;
}

}  // namespace

std::string_view errorMeasureName(ErrorMeasure measure) { return nameIn(kMeasures, measure); }

ErrorMeasure parseErrorMeasure(std::string_view name) {
  return valueIn(kMeasures, name, "objective");
}

std::string_view targetName(Target target) { return nameIn(kTargets, target); }

Target parseTarget(std::string_view name) { return valueIn(kTargets, name, "truth"); }

void validateTuneRequest(const TuneRequest& r) {
  if (r.scenes.empty()) throw Error("tune: no scene given");
  for (const std::string& scene : r.scenes) checkSceneSource(scene);
  validateOverrides(r.view);
  if (r.techniques.empty()) throw Error("tune: no technique selected");
  requireRange(r.leakWeight, 1.0, 100.0, "--leak-weight");
  if (r.budgetMs && !(*r.budgetMs > 0.0 && std::isfinite(*r.budgetMs))) {
    throw Error("--budget-ms must be a positive number of milliseconds");
  }
  if (r.budgetMib && !(*r.budgetMib > 0.0 && std::isfinite(*r.budgetMib))) {
    throw Error("--budget-mib must be a positive number of MiB");
  }
  requireRange(r.frames, 2, 32, "--frames");
  if (r.measure == ErrorMeasure::Flicker && r.frames < 4) {
    throw Error("--objective flicker needs two tuning frames and two held-out ones: --frames 4 "
                "or more (" + std::to_string(r.frames) + " given)");
  }
  requireRange(r.supersample, 1, 8, "--supersample");
  truth::checkTrueShadowLightSamples(r.truthLightSamples);
  checkAreaLightSamples(r.areaLightSamples);
  if (!(r.tau > 0.0 && r.tau < 1.0)) {
    throw Error("--tau " + std::to_string(r.tau) + " is out of range (0, 1)");
  }
  requireRange(r.evaluations, 1, 10000, "--evaluations");
  requireRange(r.maxSlowdown, 1.0, 1e6, "--max-slowdown");
  for (const std::string& name : r.only) {
    std::string valid;
    bool found = false;
    for (Technique t : r.techniques) {
      gl::RenderSettings base = r.settings;
      base.technique = t;
      // A directional light's space holds every dimension another light's has.
      for (const std::string& d : dimensionNames(searchSpace(t, base, LightKind::Directional))) {
        found = found || d == name;
        if (valid.find(" " + d + ",") == std::string::npos) valid += " " + d + ",";
      }
    }
    if (!found) {
      if (!valid.empty()) valid.pop_back();
      throw Error("--only: no selected technique searches '" + name + "'; they search:" + valid);
    }
  }
  if (!(r.searchScale > 0.0 && r.searchScale <= 1.0)) {
    throw Error("--search-scale " + std::to_string(r.searchScale) + " is out of range (0, 1]");
  }
}

SearchSpace requestSpace(const TuneRequest& request, Technique technique, LightKind light) {
  gl::RenderSettings base = request.settings;
  base.technique = technique;
  return restrictedTo(searchSpace(technique, base, light), request.only);
}

std::vector<WorkUnit> workUnits(const TuneRequest& request) {
  std::vector<WorkUnit> units;
  for (const std::string& scene : request.scenes) {
    for (Technique t : request.techniques) {
      units.push_back({int(units.size()), scene, t});
    }
  }
  return units;
}

Shard parseShard(std::string_view text) {
  const size_t slash = text.find('/');
  if (slash == std::string_view::npos) {
    throw Error("--shard '" + std::string(text) + "' is not K/N (e.g. 2/8)");
  }
  Shard s{parsePositive(text.substr(0, slash), text), parsePositive(text.substr(slash + 1), text)};
  if (s.count < 1 || s.index < 1 || s.index > s.count) {
    throw Error("--shard '" + std::string(text) + "': K must be in [1, N] and N at least 1");
  }
  return s;
}

std::vector<WorkUnit> shardUnits(const std::vector<WorkUnit>& units, const Shard& shard) {
  std::vector<WorkUnit> mine;
  for (const WorkUnit& u : units) {
    if (u.index % shard.count == shard.index - 1) mine.push_back(u);
  }
  return mine;
}

}  // namespace penumbra::tune
