// The names and JSON shared by tune's unit files and its report (tune_files.h).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "penumbra/tune/tune.h"

namespace penumbra::tune {

inline constexpr const char* kUnitsFolder = "units";
inline constexpr const char* kUnitFile = "unit.json";
inline constexpr const char* kBestFile = "best.json";
inline constexpr const char* kUnitFormat = "penumbra-tune-unit-1";
inline constexpr const char* kReportFormat = "penumbra-tune-1";

// "u007-vsm": the unit's index and technique only (a scene's name is data, never a path).
std::string unitFolderName(const WorkUnit& unit);

// Everything that decides the units' results (not --shard, --out or --quiet): equal for every
// shard of one run, so a merge can tell shards of different runs apart.
nlohmann::json requestJson(const TuneRequest& request);

// A unit.json, a plain file (not a link) of at most kMaxUnitFileBytes, of format kUnitFormat and
// the layout writeUnitFiles gives it (every field the report reads, of its type; the unit's
// index, technique and folder name agreeing with its request); throws Error naming the file.
inline constexpr std::uintmax_t kMaxUnitFileBytes = 64u << 20;
nlohmann::json readUnitJson(const std::filesystem::path& path);

// The files a unit folder holds (unit.json, best.json and the frame-1 images): --merge copies
// these and nothing else, each at most kMaxUnitFileBytes.
inline constexpr const char* kUnitFiles[] = {"unit.json",         "best.json",
                                             "default_shaded.png", "default_error.png",
                                             "tuned_shaded.png",   "tuned_error.png",
                                             "target_visibility.png"};

}  // namespace penumbra::tune
