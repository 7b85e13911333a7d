// `penumbra tune` end to end on llvmpipe: a saved best setting reproduces its error through
// compare --settings, shards merged give the single run's report, budgets hold, and the search
// finds VSM's known optimum on the planar scene. Small frames and few evaluations keep each run
// to seconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "run_penumbra.h"

namespace penumbra::test {
namespace {

using nlohmann::json;

// Small enough for llvmpipe in seconds, large enough that the shadows cover hundreds of pixels.
const std::vector<std::string> kSmall{"--width", "160", "--height", "90", "--shadow-size", "512",
                                      "--frames", "2", "--supersample", "2", "-q"};

std::vector<std::string> tuneArgs(std::vector<std::string> args) {
  std::vector<std::string> all{"tune"};
  all.insert(all.end(), args.begin(), args.end());
  all.insert(all.end(), kSmall.begin(), kSmall.end());
  return all;
}

json readJson(const fs::path& path) { return json::parse(readFile(path)); }

// Every "time_ms" key removed: the measured times, the only part of a report that two runs of
// the same request may differ in.
json withoutTimes(json j) {
  if (j.is_object()) {
    j.erase("time_ms");
    for (auto& [key, value] : j.items()) value = withoutTimes(value);
  } else if (j.is_array()) {
    for (auto& value : j) value = withoutTimes(value);
  }
  return j;
}

TEST(TuneCli, ASavedBestSettingReproducesItsErrorThroughCompare) {
  ScratchFolder dir;
  const RunResult tuned =
      runPenumbra(tuneArgs({"--technique", "vsm", "--evaluations", "8", "--out", "t"}), dir.path());
  ASSERT_EQ(tuned.exitCode(), 0) << tuned.output;
  const json report = readJson(dir.path() / "t" / "tune.json");
  const json& unit = report.at("units").at(0);
  ASSERT_FALSE(unit.at("best").is_null());
  const std::string best = unit.at("best_settings_file").get<std::string>();
  EXPECT_EQ(best, "best/vsm.json");
  const double tunedRmse = unit.at("best_at_user_size").at("frame0_rmse").get<double>();
  // The tuned setting differs from the default (else this would test nothing new).
  EXPECT_LT(tunedRmse, unit.at("default_at_user_size").at("frame0_rmse").get<double>());

  const RunResult compared = runPenumbra(
      {"compare", "--settings", "t/" + best, "--supersample", "2", "--frames", "2", "-q",
       "--out", "c"},
      dir.path());
  ASSERT_EQ(compared.exitCode(), 0) << compared.output;
  const json metrics = readJson(dir.path() / "c" / "metrics.json");
  const json& vsm = metrics.at("techniques").at(0);
  ASSERT_EQ(vsm.at("technique"), "vsm");
  // The same frame, pixels and renderer: only float summation order could differ (none does,
  // both sum in pixel order in double), so the error agrees to double rounding.
  EXPECT_NEAR(vsm.at("vs_truth").at("rmse").get<double>(), tunedRmse, 1e-9);
}

TEST(TuneCli, MergedShardsGiveTheSingleRunsReport) {
  ScratchFolder dir;
  const std::vector<std::string> request{"--scene", "planar", "--scene", "contact", "--technique",
                                         "hard,vsm", "--evaluations", "4"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = request;
    args.insert(args.end(), extra.begin(), extra.end());
    return tuneArgs(args);
  };
  for (const std::string shard : {"1/3", "2/3", "3/3"}) {
    const RunResult r = runPenumbra(with({"--shard", shard, "--out", "s" + shard.substr(0, 1)}),
                                    dir.path());
    ASSERT_EQ(r.exitCode(), 0) << r.output;
  }
  const RunResult merged =
      runPenumbra({"tune", "--merge", "s1", "s2", "s3", "--out", "merged", "-q"}, dir.path());
  ASSERT_EQ(merged.exitCode(), 0) << merged.output;
  const RunResult single = runPenumbra(with({"--out", "single"}), dir.path());
  ASSERT_EQ(single.exitCode(), 0) << single.output;

  EXPECT_EQ(withoutTimes(readJson(dir.path() / "merged" / "tune.json")),
            withoutTimes(readJson(dir.path() / "single" / "tune.json")));
  int bestFiles = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir.path() / "single" / "best")) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), dir.path() / "single");
    EXPECT_EQ(readFile(dir.path() / "merged" / relative), readFile(entry.path())) << relative;
    ++bestFiles;
  }
  EXPECT_EQ(bestFiles, 4);  // two scenes x two techniques, best/NN-scene/<technique>.json
  EXPECT_TRUE(fs::exists(dir.path() / "merged" / "index.html"));

  // A missing shard is named, not merged silently into a partial report.
  const RunResult partial =
      runPenumbra({"tune", "--merge", "s1", "s3", "--out", "partial", "-q"}, dir.path());
  EXPECT_EQ(partial.exitCode(), 1);
  EXPECT_NE(partial.output.find("units missing from the report: 1 (planar × vsm)"),
            std::string::npos)
      << partial.output;
  // Shards of another request are refused.
  const RunResult other = runPenumbra(
      tuneArgs({"--scene", "planar", "--technique", "hard", "--evaluations", "3", "--shard",
                "1/1", "--out", "other"}),
      dir.path());
  ASSERT_EQ(other.exitCode(), 0) << other.output;
  const RunResult mixed =
      runPenumbra({"tune", "--merge", "s1", "other", "--out", "mixed", "-q"}, dir.path());
  EXPECT_EQ(mixed.exitCode(), 1);
  EXPECT_NE(mixed.output.find("different tune request"), std::string::npos) << mixed.output;
}

// The settings a budget refused and checks that no eligible one, and no returned one, exceeds it.
struct BudgetCheck {
  int refused = 0;
  int eligible = 0;
};

BudgetCheck checkBudget(const json& report, const char* key, double limit, double scale) {
  BudgetCheck c;
  for (const json& unit : report.at("units")) {
    for (const json& e : unit.at("evaluations")) {
      if (e.at("eligible").get<bool>()) {
        ++c.eligible;
        EXPECT_LE(e.at(key).get<double>() * scale, limit);
      } else if (e.at("status").get<std::string>().rfind("over the", 0) == 0) {
        ++c.refused;
        EXPECT_GT(e.at(key).get<double>() * scale, limit);
      }
    }
    if (!unit.at("best").is_null()) {
      EXPECT_LE(unit.at("best_at_user_size").at(key).get<double>() * scale, limit);
    }
  }
  return c;
}

TEST(TuneCli, NoReturnedSettingExceedsABudget) {
  ScratchFolder dir;
  const std::vector<std::string> request{"--scene", "planar", "--technique", "vsm,evsm4",
                                         "--evaluations", "10"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = request;
    args.insert(args.end(), extra.begin(), extra.end());
    return tuneArgs(args);
  };
  // Unbudgeted first: its settings' times and memory place budgets that refuse some of them.
  const RunResult unbudgeted = runPenumbra(with({"--out", "free"}), dir.path());
  ASSERT_EQ(unbudgeted.exitCode(), 0) << unbudgeted.output;
  std::vector<double> times, mibs;
  const json report = readJson(dir.path() / "free" / "tune.json");
  for (const json& unit : report.at("units")) {
    for (const json& e : unit.at("evaluations")) {
      if (!e.at("eligible").get<bool>()) continue;
      times.push_back(e.at("time_ms").get<double>());
      mibs.push_back(e.at("memory_bytes").get<double>() / (1024.0 * 1024.0));
    }
  }
  ASSERT_GE(times.size(), 4u);
  std::sort(times.begin(), times.end());
  std::sort(mibs.begin(), mibs.end());
  // A third of the way up: about two thirds of what the search tries lie above each, so a run
  // on a machine busier or quieter than the first by a good margin still meets and misses them.
  // As the command line carries them (std::to_string's six decimals): a setting exactly at the
  // budget must be judged against the budget the tool was given.
  const double budgetMs = std::stod(std::to_string(times[times.size() / 3]));
  const double budgetMib = std::stod(std::to_string(mibs[mibs.size() / 3]));

  const RunResult timed =
      runPenumbra(with({"--budget-ms", std::to_string(budgetMs), "--out", "timed"}), dir.path());
  ASSERT_EQ(timed.exitCode(), 0) << timed.output;
  const BudgetCheck t = checkBudget(readJson(dir.path() / "timed" / "tune.json"), "time_ms",
                                    budgetMs, 1.0);
  EXPECT_GT(t.refused, 0);  // the budget did refuse settings the search tried
  EXPECT_GT(t.eligible, 0);

  const RunResult sized = runPenumbra(
      with({"--budget-mib", std::to_string(budgetMib), "--out", "sized"}), dir.path());
  ASSERT_EQ(sized.exitCode(), 0) << sized.output;
  const BudgetCheck m = checkBudget(readJson(dir.path() / "sized" / "tune.json"), "memory_bytes",
                                    budgetMib, 1.0 / (1024.0 * 1024.0));
  EXPECT_GT(m.refused, 0);
  EXPECT_GT(m.eligible, 0);

  // A budget nothing meets: no setting is returned, and no best file written.
  const RunResult none = runPenumbra(
      tuneArgs({"--scene", "planar", "--technique", "hard", "--evaluations", "3", "--budget-ms",
                "0.000001", "--out", "none"}),
      dir.path());
  ASSERT_EQ(none.exitCode(), 0) << none.output;
  const json nothing = readJson(dir.path() / "none" / "tune.json");
  EXPECT_TRUE(nothing.at("units").at(0).at("best").is_null());
  EXPECT_FALSE(fs::exists(dir.path() / "none" / "best" / "hard.json"));
}

TEST(TuneCli, FindsVsmsVarianceFloorAtTheLowerBoundOnThePlanarScene) {
  // thesis §3.2: on a planar receiver under a planar occluder VSM is exact but for its floor,
  // which lifts the umbra's visibility from 0 to floor / (floor + (d - mean)^2): the least
  // error is at the registry's lower bound, 0.
  ScratchFolder dir;
  const RunResult r = runPenumbra(
      tuneArgs({"--scene", "planar", "--technique", "vsm", "--only", "minVariance",
                "--param", "minVariance=0.002", "--evaluations", "20", "--out", "t"}),
      dir.path());
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  const json unit = readJson(dir.path() / "t" / "tune.json").at("units").at(0);
  ASSERT_FALSE(unit.at("best").is_null());
  const json& point = unit.at("evaluations").at(unit.at("best").get<size_t>()).at("point");
  ASSERT_EQ(point.size(), 1u);  // --only: one dimension searched
  EXPECT_LT(std::stod(point.at("minVariance").get<std::string>()), 1e-6);
}

}  // namespace
}  // namespace penumbra::test
