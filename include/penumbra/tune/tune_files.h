// What `penumbra tune` writes (docs/tune.md). Every unit (a scene x technique) writes its own
// folder, `units/uNNN-<technique>/`: unit.json (the request, the search space, every evaluation,
// the result) and its frame-0 images. The report — tune.json, best/, index.html and the
// frontier plots — is assembled from the unit folders alone, so a single run and a merge of
// shards (each a subset of the units) give the same report: only measured times differ, each
// under a "time_ms" key.
#pragma once

#include <filesystem>
#include <vector>

#include "penumbra/tune/tune.h"

namespace penumbra::tune {

// Writes `folder`/units/<unit>/ for one finished unit.
void writeUnitFiles(const TuneRequest& request, const UnitResult& result,
                    const std::filesystem::path& folder);

// `folder`/units, empty: a shard's output even when it holds no unit (more array tasks than
// units), so --merge can tell it from a folder that is not a shard.
void createUnitsFolder(const std::filesystem::path& folder);

// Copies the unit folders of shard outputs (each a `tune --shard` output folder) into
// `folder`/units: their known files only, plain and bounded. Throws Error, before copying
// anything, when a folder is not a shard output, when none holds a unit, when two hold the same
// unit, when their requests differ or a unit file is not as penumbra writes it.
void gatherUnits(const std::vector<std::filesystem::path>& shardFolders,
                 const std::filesystem::path& folder);

// From `folder`/units: tune.json, best/<technique>.json (best/<NN-scene>/<technique>.json for
// several scenes), index.html and plots/. Throws Error naming the missing units when the set
// is incomplete.
void writeTuneReport(const std::filesystem::path& folder);

}  // namespace penumbra::tune
