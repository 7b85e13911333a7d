// The report of a tune run, from its unit folders alone (tune_files.h): tune.json, best/,
// index.html and the frontier plots.
#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>

#include "frontier.h"
#include "penumbra/compare/html_text.h"
#include "penumbra/error.h"
#include "penumbra/output_journal.h"
#include "penumbra/text_file.h"
#include "penumbra/tune/tune_files.h"
#include "tune_json.h"

namespace penumbra::tune {
namespace {

namespace fs = std::filesystem;
using compare::escapeHtml;
using compare::fixedDigits;
using nlohmann::json;

constexpr double kMiB = 1024.0 * 1024.0;

// A scene's folder name under best/ when a run has several: its place and its name's letters.
std::string sceneFolder(int index, const std::string& scene) {
  std::string stem = fs::path(scene).stem().string();
  std::string safe;
  for (char c : stem) {
    safe += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
    if (safe.size() == 40) break;
  }
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%02d-", index);
  return prefix + safe;
}

std::string number(const json& j, int digits = 4) {
  return j.is_number() ? fixedDigits(j.get<double>(), digits) : "–";
}

std::string mib(const json& bytes) {
  return bytes.is_number() ? fixedDigits(bytes.get<double>() / kMiB, 1) : "–";
}

std::string pointText(const json& point) {
  std::string text;
  for (const auto& [name, value] : point.items()) {
    text += (text.empty() ? "" : ", ") + name + "=" + value.get<std::string>();
  }
  return text;
}

// Where a unit's point differs from the user's (evaluation 0).
std::string changedText(const json& unit, int evaluation) {
  const json& start = unit.at("evaluations").at(0).at("point");
  const json& point = unit.at("evaluations").at(size_t(evaluation)).at("point");
  std::string text;
  for (const auto& [name, value] : point.items()) {
    if (start.value(name, json()) == value) continue;
    text += (text.empty() ? "" : ", ") + name + " " + start.at(name).get<std::string>() + " → " +
            value.get<std::string>();
  }
  return text.empty() ? "(the user's setting)" : text;
}

std::string spaceHtml(const json& unit) {
  std::ostringstream h;
  h << "<ul class=space>";
  for (const json& d : unit.at("space").at("dimensions")) {
    h << "<li><b>" << escapeHtml(d.at("kind").get<std::string>() == "param" ? "param " : "")
      << escapeHtml(d.at("name").get<std::string>()) << "</b>: ";
    if (d.contains("min")) {
      h << "[" << d.at("min").get<double>() << ", " << d.at("max").get<double>() << "] "
        << escapeHtml(d.at("scale").get<std::string>());
    } else {
      std::string values;
      for (const json& v : d.at("values")) values += (values.empty() ? "" : ", ") + v.get<std::string>();
      h << "{" << escapeHtml(values) << "}";
    }
    h << " <span class=note>" << escapeHtml(d.at("description").get<std::string>()) << "</span></li>";
  }
  for (const json& f : unit.at("space").at("fixed")) {
    h << "<li>fixed <b>" << escapeHtml(f.at("name").get<std::string>()) << "</b> = "
      << escapeHtml(f.at("value").get<std::string>()) << " <span class=note>"
      << escapeHtml(f.at("reason").get<std::string>()) << "</span></li>";
  }
  h << "</ul>";
  return h.str();
}

struct SceneUnits {
  int index = 0;
  std::string scene;
  std::vector<const json*> units;
};

void budgetTable(std::ostringstream& h, const std::vector<CostPoint>& front, const char* unit,
                 const std::string& what) {
  h << "<table><tr><th>" << what << " budget</th><th>best technique</th><th>tuning error</th>"
    << "<th>its " << what << "</th></tr>";
  for (size_t i = 0; i < front.size(); ++i) {
    h << "<tr><td>≥ " << fixedDigits(front[i].cost, 2) << " " << unit;
    if (i + 1 < front.size()) h << " and < " << fixedDigits(front[i + 1].cost, 2) << " " << unit;
    h << "</td><td>" << escapeHtml(front[i].technique) << " #" << front[i].evaluation
      << "</td><td>" << fixedDigits(front[i].error, 4) << "</td><td>"
      << fixedDigits(front[i].cost, 2) << " " << unit << "</td></tr>";
  }
  h << "</table>";
}

}  // namespace

void writeTuneReport(const fs::path& folder) {
  // Every unit, in order.
  std::map<int, json> byIndex;
  const fs::path unitsDir = folder / kUnitsFolder;
  if (fs::is_directory(fs::symlink_status(unitsDir))) {
    for (const fs::directory_entry& entry : fs::directory_iterator(unitsDir)) {
      if (!entry.is_directory() || entry.is_symlink()) continue;
      json unit = readUnitJson(entry.path() / kUnitFile);
      const int index = unit.at("unit").at("index").get<int>();
      if (byIndex.count(index)) {
        throw Error("tune: unit " + std::to_string(index) + " appears twice in " +
                    unitsDir.string());
      }
      byIndex.emplace(index, std::move(unit));
    }
  }
  if (byIndex.empty()) throw Error("tune: no unit in " + unitsDir.string());
  const json request = byIndex.begin()->second.at("request");
  const std::vector<std::string> scenes = request.at("scenes").get<std::vector<std::string>>();
  const std::vector<std::string> techniques =
      request.at("techniques").get<std::vector<std::string>>();
  const int expected = int(scenes.size() * techniques.size());
  std::string missing;
  for (int i = 0; i < expected; ++i) {
    if (!byIndex.count(i)) {
      missing += (missing.empty() ? "" : ", ") + std::to_string(i) + " (" +
                 scenes[size_t(i) / techniques.size()] + " × " +
                 techniques[size_t(i) % techniques.size()] + ")";
    }
  }
  if (!missing.empty()) throw Error("tune: units missing from the report: " + missing);
  for (const auto& [index, unit] : byIndex) {
    if (index < 0 || index >= expected || unit.at("request") != request) {
      throw Error("tune: unit " + std::to_string(index) + " in " + unitsDir.string() +
                  " belongs to another tune request");
    }
  }

  // tune.json: the request once, then every unit without it.
  json all;
  all["format"] = kReportFormat;
  all["request"] = request;
  json units = json::array();
  for (const auto& [index, unit] : byIndex) {
    json u = unit;
    u.erase("request");
    u.erase("format");
    u["best_settings_file"] = nullptr;
    units.push_back(std::move(u));
  }

  // best/: each unit's returned setting, as render, compare and the viewer load it.
  std::vector<SceneUnits> perScene(scenes.size());
  for (size_t s = 0; s < scenes.size(); ++s) perScene[s] = {int(s), scenes[s], {}};
  size_t k = 0;
  for (const auto& [index, unit] : byIndex) {
    const size_t sceneIndex = size_t(index) / techniques.size();
    perScene[sceneIndex].units.push_back(&unit);
    if (!unit.at("best").is_null()) {
      fs::path target = fs::path("best");
      if (scenes.size() > 1) target /= sceneFolder(int(sceneIndex), scenes[sceneIndex]);
      target /= unit.at("unit").at("technique").get<std::string>() + ".json";
      createOutputDirectory(folder / target.parent_path());
      const fs::path source = unitsDir / unitFolderName({index, "", parseTechnique(
                                  unit.at("unit").at("technique").get<std::string>())}) /
                              kBestFile;
      recordOutput(folder / target);  // listed before it exists (output_journal.h)
      fs::copy_file(source, folder / target, fs::copy_options::overwrite_existing);
      units[k]["best_settings_file"] = target.generic_string();
    }
    ++k;
  }
  all["units"] = units;
  writeTextFile(folder / "tune.json", all.dump(2) + "\n");

  // index.html and the frontier plots.
  createOutputDirectory(folder / "plots");
  std::ostringstream h;
  h << "<!doctype html><html><head><meta charset=utf-8><title>penumbra tune</title><style>"
       "body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse;"
       "margin:1em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
       "th{background:#eee}td.l{text-align:left}.note{color:#666;font-size:90%}"
       "img{max-width:32%;margin:2px}.space{font-size:90%}</style></head><body>"
    << "<h1>penumbra tune</h1><p>Objective <b>"
    << escapeHtml(request.at("objective").get<std::string>()) << "</b> against the <b>"
    << escapeHtml(request.at("truth").get<std::string>() == "raytraced"
                      ? "ray-traced true shadow"
                      : "supersampled filtered reference")
    << "</b>, tuned on camera-path frames 1–" << request.at("tuning_frames").get<int>()
    << " and reported on the held-out frames " << request.at("tuning_frames").get<int>() + 1
    << "–" << request.at("frames").get<int>() << "; at most "
    << request.at("evaluations").get<int>() << " evaluations per technique. Budgets: time "
    << (request.at("budget_ms").is_null() ? "none" : number(request.at("budget_ms"), 2) + " ms")
    << ", memory "
    << (request.at("budget_mib").is_null() ? "none" : number(request.at("budget_mib"), 1) + " MiB")
    << ". Frame " << request.at("settings").at("width").get<int>() << "×"
    << request.at("settings").at("height").get<int>()
    << "; the error and time columns below are measured again at that size for the user's and "
       "the returned setting. <code>tune.json</code> holds every evaluation.</p>";

  for (const SceneUnits& scene : perScene) {
    const json& first = *scene.units.front();
    h << "<h2>" << escapeHtml(first.at("scene_name").get<std::string>()) << " <span class=note>("
      << escapeHtml(scene.scene) << ")</span></h2>";
    h << "<table><tr><th>technique</th><th>setting</th><th>tuning error</th>"
         "<th>held-out error</th><th>frame 1 RMSE vs target</th><th>time (ms)</th>"
         "<th>memory (MiB)</th><th>evaluations</th><th class=l>what changed</th></tr>";
    std::vector<CostPoint> byTime, byMemory;
    for (const json* unitPtr : scene.units) {
      const json& unit = *unitPtr;
      const std::string id = unit.at("unit").at("technique").get<std::string>();
      const json& d = unit.at("default_at_user_size");
      const json& b = unit.at("best_at_user_size");
      const int evaluations = int(unit.at("evaluations").size());
      auto row = [&](const char* label, const json& m, const std::string& changed) {
        h << "<tr><td class=l>" << escapeHtml(id) << "</td><td class=l>" << label << "</td><td>"
          << number(m.value("tune_error", json())) << "</td><td>"
          << number(m.value("held_out_error", json())) << "</td><td>"
          << number(m.value("frame0_rmse", json())) << "</td><td>"
          << number(m.value("time_ms", json()), 2) << "</td><td>"
          << mib(m.value("memory_bytes", json())) << "</td><td>" << evaluations
          << "</td><td class=l>" << escapeHtml(changed) << "</td></tr>";
      };
      row("default", d, d.at("eligible").get<bool>() ? "" : d.at("status").get<std::string>());
      if (b.is_null()) {
        h << "<tr><td class=l>" << escapeHtml(id)
          << "</td><td class=l>tuned</td><td colspan=7 class=l>no eligible setting (each "
             "evaluation's status in tune.json says why)</td></tr>";
      } else {
        row("tuned", b, changedText(unit, unit.at("best").get<int>()));
      }
      int e = 0;
      for (const json& ev : unit.at("evaluations")) {
        if (ev.at("eligible").get<bool>()) {
          byTime.push_back({id, e, ev.at("time_ms").get<double>(), ev.at("tune_error").get<double>()});
          byMemory.push_back(
              {id, e, ev.at("memory_bytes").get<double>() / kMiB, ev.at("tune_error").get<double>()});
        }
        ++e;
      }
    }
    h << "</table>";
    const std::string prefix = scenes.size() > 1 ? sceneFolder(scene.index, scene.scene) + "_" : "";
    const std::string errorLabel = request.at("objective").get<std::string>() + " on the tuning frames";
    if (!byTime.empty()) {
      plotFrontier(byTime, techniques, "warm frame time (ms, log scale)", errorLabel,
                   first.at("scene_name").get<std::string>() + ": error against time",
                   folder / "plots" / (prefix + "frontier_time.png"));
      plotFrontier(byMemory, techniques, "memory (MiB, log scale)", errorLabel,
                   first.at("scene_name").get<std::string>() + ": error against memory",
                   folder / "plots" / (prefix + "frontier_memory.png"));
      h << "<h3>The quality–cost frontier</h3><p>Every eligible setting the search measured "
           "(points, by technique): its error on the tuning frames and its time (the camera "
           "path's last frame, warm) at the search's frame size, and its memory estimate at "
           "the full size; the frontier is the least error any setting reaches within a budget. "
           "#N is the technique's evaluation N in <code>tune.json</code> (#0: the given "
           "setting).</p>"
        << "<img src=\"plots/" << prefix << "frontier_time.png\" style=\"max-width:49%\">"
        << "<img src=\"plots/" << prefix << "frontier_memory.png\" style=\"max-width:49%\">";
      h << "<h4>The best technique per time budget</h4>";
      budgetTable(h, paretoFront(byTime), "ms", "time");
      h << "<h4>The best technique per memory budget</h4>";
      budgetTable(h, paretoFront(byMemory), "MiB", "memory");
    }
    h << "<h3>Frame 1, the user's setting against the tuned one</h3>";
    for (const json* unitPtr : scene.units) {
      const json& unit = *unitPtr;
      const std::string id = unit.at("unit").at("technique").get<std::string>();
      const std::string dir =
          std::string(kUnitsFolder) + "/" +
          unitFolderName({unit.at("unit").at("index").get<int>(), "", parseTechnique(id)});
      h << "<h4>" << escapeHtml(id) << "</h4><div>"
        << "<img src=\"" << dir << "/default_shaded.png\" title=\"default\">"
        << "<img src=\"" << dir << "/default_error.png\" title=\"default: error\">";
      if (!unit.at("best").is_null()) {
        h << "<img src=\"" << dir << "/tuned_shaded.png\" title=\"tuned\">"
          << "<img src=\"" << dir << "/tuned_error.png\" title=\"tuned: error\">";
      }
      h << "<img src=\"" << dir << "/target_visibility.png\" title=\"target visibility\"></div>"
        << "<details><summary>search space</summary>" << spaceHtml(unit) << "</details>";
      if (!unit.at("best").is_null()) {
        h << "<p class=note>tuned: " << escapeHtml(pointText(
                 unit.at("evaluations").at(size_t(unit.at("best").get<int>())).at("point")))
          << "</p>";
      }
    }
  }
  h << "</body></html>\n";
  writeTextFile(folder / "index.html", h.str());
}

}  // namespace penumbra::tune
