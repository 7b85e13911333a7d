// `penumbra bench --passes` writes what it printed: every CSV row as many fields as its header,
// the JSON's rows with the fastest frame's times and the medians beside them (null where a pass
// has no yardstick), and as many frames as asked, 15 when --repeat is not given.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_penumbra.h"

namespace penumbra::test {
namespace {

// One CSV line's fields; a field in double quotes may hold commas and doubled quotes.
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

nlohmann::json benchPasses(const ScratchFolder& scratch, std::vector<std::string> extra) {
  std::vector<std::string> args{"bench",         "--passes", "--technique", "vsm",
                                "--shadow-size", "64",       "--width",     "32",
                                "--height",      "18",       "--out",       "out"};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult run = runPenumbra(args, scratch.path());
  EXPECT_EQ(run.exitCode(), 0) << run.output;
  return nlohmann::json::parse(readFile(scratch.path() / "out" / "passes.json"));
}

TEST(BenchPassesOutput, TheCsvAndJsonHoldEveryRowWithItsMedians) {
  ScratchFolder scratch;
  const nlohmann::json record = benchPasses(scratch, {});
  EXPECT_EQ(record["repeats"], 15) << "the --passes default";
  const nlohmann::json& rows = record["rows"];
  ASSERT_EQ(rows.size(), 5u);  // encode, prefilter, mips, camera, fused
  for (const nlohmann::json& row : rows) {
    SCOPED_TRACE(row["pass"].get<std::string>());
    EXPECT_GT(row["pass_ms"].get<double>(), 0.0);
    EXPECT_GT(row["pass_median_ms"].get<double>(), 0.0);
    EXPECT_GT(row["baseline_median_ms"].get<double>(), 0.0);
    const bool hasYardstick = !row["yardstick"].get<std::string>().empty();
    EXPECT_EQ(row["yardstick_median_ms"].is_number(), hasYardstick);
    EXPECT_EQ(row["yardstick_ms"].is_number(), hasYardstick);
  }

  std::istringstream csv(readFile(scratch.path() / "out" / "passes.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const std::vector<std::string> header = csvFields(line);
  ASSERT_EQ(header.size(), 13u);
  EXPECT_EQ(header[10], "pass_median_ms");
  EXPECT_EQ(header[12], "yardstick_median_ms");
  size_t index = 0;
  while (std::getline(csv, line)) {
    ASSERT_LT(index, rows.size());
    const std::vector<std::string> fields = csvFields(line);
    ASSERT_EQ(fields.size(), header.size()) << line;
    const nlohmann::json& row = rows[index++];
    EXPECT_EQ(fields[2], row["pass"].get<std::string>());
    // The CSV prints 6 significant digits: the same times as the JSON's to that precision.
    EXPECT_NEAR(std::stod(fields[3]), row["pass_ms"].get<double>(),
                1e-5 * row["pass_ms"].get<double>());
    EXPECT_NEAR(std::stod(fields[10]), row["pass_median_ms"].get<double>(),
                1e-5 * row["pass_median_ms"].get<double>());
    EXPECT_EQ(fields[12].empty(), row["yardstick"].get<std::string>().empty()) << line;
  }
  EXPECT_EQ(index, rows.size());
}

TEST(BenchPassesOutput, AGivenRepeatIsKept) {
  ScratchFolder scratch;
  EXPECT_EQ(benchPasses(scratch, {"--repeat", "2"})["repeats"], 2);
}

}  // namespace
}  // namespace penumbra::test
