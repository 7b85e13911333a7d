// Unit names, the request's JSON and reading unit files (tune_json.h).
#include "tune_json.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gl/settings_json.h"

namespace penumbra::tune {

using nlohmann::json;

std::string unitFolderName(const WorkUnit& unit) {
  char index[16];
  std::snprintf(index, sizeof index, "u%03d-", unit.index);
  return index + std::string(techniqueId(unit.technique));
}

json requestJson(const TuneRequest& r) {
  gl::Settings settings;
  settings.scene = "";
  settings.techniques = r.techniques;
  settings.render = r.settings;
  settings.view = r.view;
  json j;
  j["scenes"] = r.scenes;
  json techniques = json::array();
  for (Technique t : r.techniques) techniques.push_back(std::string(techniqueId(t)));
  j["techniques"] = techniques;
  json base = json::parse(gl::settingsJson(settings));
  base.erase("scene");
  j["settings"] = base;
  j["only"] = r.only;
  j["truth"] = std::string(targetName(r.target));
  j["objective"] = std::string(errorMeasureName(r.measure));
  j["leak_weight"] = r.leakWeight;
  j["budget_ms"] = r.budgetMs ? json(*r.budgetMs) : json(nullptr);
  j["budget_mib"] = r.budgetMib ? json(*r.budgetMib) : json(nullptr);
  j["frames"] = r.frames;
  j["tuning_frames"] = (r.frames + 1) / 2;
  j["supersample"] = r.supersample;
  j["truth_samples"] = r.truthLightSamples;
  j["area_samples"] = r.areaLightSamples;
  j["tau"] = r.tau;
  j["evaluations"] = r.evaluations;
  j["search_scale"] = r.searchScale;
  j["max_slowdown"] = r.maxSlowdown;
  return j;
}

json readUnitJson(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw Error(path.string() + ": cannot read (" + ec.message() + ")");
  if (size > kMaxUnitFileBytes) {
    throw Error(path.string() + ": " + std::to_string(size) + " bytes, more than a unit file's " +
                std::to_string(kMaxUnitFileBytes));
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  json j;
  try {
    j = json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw Error(path.string() + ": not JSON (" + e.what() + ")");
  }
  if (!j.is_object() || j.value("format", std::string()) != kUnitFormat) {
    throw Error(path.string() + ": not a penumbra tune unit (format " + kUnitFormat + ")");
  }
  return j;
}

}  // namespace penumbra::tune
