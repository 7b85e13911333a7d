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
  j["tuning_frames"] = tuningFrames(r);
  j["supersample"] = r.supersample;
  j["truth_samples"] = r.truthLightSamples;
  j["area_samples"] = r.areaLightSamples;
  j["tau"] = r.tau;
  j["evaluations"] = r.evaluations;
  j["search_scale"] = r.searchScale;
  j["max_slowdown"] = r.maxSlowdown;
  return j;
}

namespace {

// Throws json::exception (turned into Error by the caller) where the layout differs.
void checkMeasurement(const json& m) {
  (void)m.at("eligible").get<bool>();
  (void)m.at("status").get<std::string>();
  (void)m.at("memory_bytes").get<double>();
  if (m.at("measured").get<bool>()) {
    for (const char* key : {"tune_error", "held_out_error", "tune_rmse", "held_out_rmse",
                            "frame0_rmse", "frame0_leak_share", "frame0_dark_share", "time_ms"}) {
      (void)m.at(key).get<double>();
    }
  }
}

void checkUnitLayout(const json& j, const std::filesystem::path& path) {
  const json& request = j.at("request");
  const auto scenes = request.at("scenes").get<std::vector<std::string>>();
  const auto techniques = request.at("techniques").get<std::vector<std::string>>();
  const int index = j.at("unit").at("index").get<int>();
  if (techniques.empty() || index < 0 || size_t(index) >= scenes.size() * techniques.size()) {
    throw Error(path.string() + ": unit index " + std::to_string(index) +
                " is outside its request's scenes x techniques");
  }
  const std::string technique = j.at("unit").at("technique").get<std::string>();
  if (technique != techniques[size_t(index) % techniques.size()] ||
      j.at("unit").at("scene").get<std::string>() != scenes[size_t(index) / techniques.size()]) {
    throw Error(path.string() + ": unit " + std::to_string(index) +
                " names another scene or technique than its request places there");
  }
  const std::string folder = path.parent_path().filename().string();
  if (folder != unitFolderName({index, "", parseTechnique(technique)})) {
    throw Error(path.string() + ": a unit folder named '" + folder + "' holds unit " +
                std::to_string(index) + " (" + technique + ")");
  }
  (void)j.at("scene_name").get<std::string>();
  (void)j.at("device").get<std::string>();
  for (const json& d : j.at("space").at("dimensions")) {
    (void)d.at("name").get<std::string>();
    (void)d.at("kind").get<std::string>();
    (void)d.at("description").get<std::string>();
    if (d.contains("min")) {
      (void)d.at("min").get<double>();
      (void)d.at("max").get<double>();
      (void)d.at("scale").get<std::string>();
    } else {
      (void)d.at("values").get<std::vector<std::string>>();
    }
  }
  for (const json& f : j.at("space").at("fixed")) {
    for (const char* key : {"name", "value", "reason"}) (void)f.at(key).get<std::string>();
  }
  const json& evaluations = j.at("evaluations");
  if (!evaluations.is_array() || evaluations.empty()) {
    throw Error(path.string() + ": a unit without evaluations");
  }
  for (const json& e : evaluations) {
    checkMeasurement(e);
    for (const auto& [name, value] : e.at("point").items()) (void)value.get<std::string>();
  }
  const json& best = j.at("best");
  if (!best.is_null() && (best.get<int>() < 0 || size_t(best.get<int>()) >= evaluations.size())) {
    throw Error(path.string() + ": best evaluation " + best.dump() + " is not one of its " +
                std::to_string(evaluations.size()));
  }
  checkMeasurement(j.at("default_at_user_size"));
  if (best.is_null() != j.at("best_at_user_size").is_null()) {
    throw Error(path.string() + ": best and best_at_user_size disagree");
  }
  if (!best.is_null()) checkMeasurement(j.at("best_at_user_size"));
}

}  // namespace

json readUnitJson(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(path))) {
    throw Error(path.string() + ": missing, or not a plain file (a link is not followed)");
  }
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
  try {
    checkUnitLayout(j, path);
  } catch (const json::exception& e) {
    throw Error(path.string() + ": not a tune unit as penumbra writes it (" + e.what() + ")");
  }
  return j;
}

}  // namespace penumbra::tune
