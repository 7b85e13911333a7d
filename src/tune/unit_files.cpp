// A unit's folder (tune_files.h): unit.json, its best settings file and its frame-0 images; and
// gathering the unit folders of shards.
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "penumbra/compare/report_plots.h"
#include "penumbra/error.h"
#include "penumbra/gl/settings_json.h"
#include "penumbra/image_io.h"
#include "penumbra/output_journal.h"
#include "penumbra/text_file.h"
#include "penumbra/tune/tune_files.h"
#include "tune_json.h"

namespace penumbra::tune {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Signed errors beyond half the visibility range saturate the heat maps (as compare's).
constexpr double kHeatMapRange = 0.5;

json measurementJson(const Measurement& m) {
  json j;
  j["eligible"] = m.eligible;
  j["status"] = m.status;
  j["measured"] = m.measured;
  if (m.measured) {
    j["tune_error"] = m.tuneError;
    j["held_out_error"] = m.heldOutError;
    j["tune_rmse"] = m.tuneRmse;
    j["held_out_rmse"] = m.heldOutRmse;
    j["frame0_rmse"] = m.frame0Rmse;
    j["frame0_leak_share"] = m.frame0LeakShare;
    j["frame0_dark_share"] = m.frame0DarkShare;
    j["time_ms"] = m.timeMs;
  } else if (m.tooSlow) {
    j["time_ms"] = m.timeMs;  // its first frame's, which refused it
  }
  j["memory_bytes"] = m.memoryBytes;
  return j;
}

json spaceJson(const SearchSpace& space) {
  json dims = json::array();
  for (const Dimension& d : space.dimensions) {
    json j;
    j["name"] = d.name;
    j["kind"] = d.isParam ? "param" : "render";
    if (d.continuous) {
      j["min"] = d.min;
      j["max"] = d.max;
      j["scale"] = d.scale == Scale::Linear ? "linear" : d.scale == Scale::Log ? "log" : "zero-log";
    } else {
      j["values"] = d.values;
      j["ordinal"] = d.ordinal;
    }
    j["description"] = d.description;
    dims.push_back(j);
  }
  json fixed = json::array();
  for (const FixedSetting& f : space.fixed) {
    fixed.push_back({{"name", f.name}, {"value", f.value}, {"reason", f.reason}});
  }
  return {{"dimensions", dims}, {"fixed", fixed}};
}

json pointJson(const SearchSpace& space, const Point& point) {
  json j = json::object();
  for (size_t i = 0; i < point.size(); ++i) j[space.dimensions[i].name] = point[i];
  return j;
}

// Frame 0's target visibility as a grey image: pixels without a surface (-1) as lit sky.
Image displayableVisibility(const Image& visibility) {
  Image out = visibility;
  for (float& v : out.data()) {
    if (v < 0.0f) v = 1.0f;
  }
  return out;
}

}  // namespace

void writeUnitFiles(const TuneRequest& request, const UnitResult& r, const fs::path& folder) {
  const fs::path dir = folder / kUnitsFolder / unitFolderName(r.unit);
  createOutputDirectory(dir);
  json j;
  j["format"] = kUnitFormat;
  j["request"] = requestJson(request);
  j["unit"] = {{"index", r.unit.index},
               {"scene", r.unit.scene},
               {"technique", std::string(techniqueId(r.unit.technique))}};
  j["scene_name"] = r.sceneName;
  j["device"] = r.device;
  j["space"] = spaceJson(r.space);
  json evaluations = json::array();
  for (const Evaluation& e : r.evaluations) {
    json ej = measurementJson(e.measurement);
    ej["point"] = pointJson(r.space, e.point);
    evaluations.push_back(ej);
  }
  j["evaluations"] = evaluations;
  j["rounds"] = r.rounds;
  j["best"] = r.best >= 0 ? json(r.best) : json(nullptr);
  j["default_at_user_size"] = measurementJson(r.defaultAtUserSize);
  j["best_at_user_size"] = r.bestAtUserSize ? measurementJson(*r.bestAtUserSize) : json(nullptr);
  j["run"] = {{"time_ms", r.seconds * 1000.0}};
  writeTextFile(dir / kUnitFile, j.dump(2) + "\n");

  if (r.best >= 0) {
    gl::Settings best;
    best.scene = r.unit.scene;
    best.techniques = {r.unit.technique};
    best.render = r.bestSettings;
    best.view = request.view;
    gl::writeSettingsFile(dir / kBestFile, best);
  }
  writeColorPng(r.defaultColor, dir / "default_shaded.png");
  GnuplotRun gnuplot(dir);  // both heat maps, one batch
  compare::plotErrorHeatMap(gnuplot, r.defaultError, kHeatMapRange,
                            std::string(techniqueId(r.unit.technique)) +
                                ", the user's setting: visibility - target",
                            dir / "default_error.png");
  writeGrey16Png(displayableVisibility(r.targetVisibility), dir / "target_visibility.png");
  if (r.best >= 0) {
    writeColorPng(r.bestColor, dir / "tuned_shaded.png");
    compare::plotErrorHeatMap(gnuplot, r.bestError, kHeatMapRange,
                              std::string(techniqueId(r.unit.technique)) +
                                  ", tuned: visibility - target",
                              dir / "tuned_error.png");
  }
  gnuplot.run();
}

void createUnitsFolder(const fs::path& folder) { createOutputDirectory(folder / kUnitsFolder); }

void gatherUnits(const std::vector<fs::path>& shardFolders, const fs::path& folder) {
  std::map<std::string, fs::path> sources;  // unit folder name -> where it is
  std::optional<json> request;
  for (const fs::path& shard : shardFolders) {
    const fs::path units = shard / kUnitsFolder;
    if (!fs::is_directory(fs::symlink_status(units))) {
      throw Error("--merge: " + shard.string() + " holds no " + kUnitsFolder +
                  " folder: is it a `penumbra tune --shard` output?");
    }
    for (const fs::directory_entry& entry : fs::directory_iterator(units)) {
      if (!entry.is_directory() || entry.is_symlink()) continue;  // only what tune writes
      const json unit = readUnitJson(entry.path() / kUnitFile);
      if (!request) {
        request = unit.at("request");
      } else if (unit.at("request") != *request) {
        throw Error("--merge: " + entry.path().string() +
                    " comes from a different tune request than the others (scenes, "
                    "techniques or options differ)");
      }
      const std::string name = entry.path().filename().string();
      if (!sources.emplace(name, entry.path()).second) {
        throw Error("--merge: unit " + name + " is in both " + sources[name].string() + " and " +
                    entry.path().string());
      }
    }
  }
  // A shard may hold no unit (an array with more tasks than units); all of them together must.
  if (sources.empty()) throw Error("--merge: the shard folders hold no unit");
  for (const auto& [name, source] : sources) {
    const fs::path target = folder / kUnitsFolder / name;
    createOutputDirectory(target);
    // The files a unit has, plain and bounded: a link planted in a shard folder is not
    // followed, nothing else in it is copied.
    for (const char* fileName : kUnitFiles) {
      const fs::path file = source / fileName;
      const fs::file_status status = fs::symlink_status(file);
      if (!fs::exists(status)) continue;  // best.json and tuned_*: only with a best setting
      if (!fs::is_regular_file(status) || fs::file_size(file) > kMaxUnitFileBytes) {
        throw Error("--merge: " + file.string() + " is not a plain file of at most " +
                    std::to_string(kMaxUnitFileBytes >> 20) + " MiB");
      }
      recordOutput(target / fileName);  // listed before it exists (output_journal.h)
      fs::copy_file(file, target / fileName);
    }
  }
}

}  // namespace penumbra::tune
