// `compare` ranks by the ray-traced truth unless told `--truth none`, and its files say which:
// metrics.json's truth block and vs_truth columns, the CSV's truth columns, the page's images.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "run_penumbra.h"

namespace penumbra::test {
namespace {

struct Report {
  int exitCode = -1;
  std::string output;
  nlohmann::json metrics;
  std::string html;
  std::string csv;
  bool truthImages = false;
};

Report compare(const std::vector<std::string>& extra) {
  ScratchFolder scratch;
  std::vector<std::string> args{"compare", "--scene",  "backyard", "--technique", "hard,pcf,vsm",
                                "--shadow-size", "256", "--width", "96", "--height", "54",
                                "--frames", "2", "--supersample", "2", "--quiet", "--out",
                                "report"};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult run = runPenumbra(args, scratch.path());
  Report report{run.exitCode(), run.output, {}, {}, {}, false};
  if (run.exitCode() == 0) {
    const auto dir = scratch.path() / "report";
    report.metrics = nlohmann::json::parse(readFile(dir / "metrics.json"));
    report.html = readFile(dir / "index.html");
    report.csv = readFile(dir / "metrics.csv");
    report.truthImages = std::filesystem::exists(dir / "images" / "truth_pixels.png") &&
                         std::filesystem::exists(dir / "images" / "vsm_truth_error.png");
  }
  return report;
}

TEST(CompareTruth, RanksByTheRayTracedTruthByDefaultAndSaysSo) {
  const Report r = compare({});
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json& truth = r.metrics["truth"];
  ASSERT_TRUE(truth.is_object());
  EXPECT_EQ(truth["kind"], "raytraced");
  EXPECT_GT(truth["pixels_measured"].get<int>(), 1000);
  EXPECT_GT(truth["camera_rays"].get<long>(), 0);
  for (const nlohmann::json& t : r.metrics["techniques"]) {
    ASSERT_TRUE(t["vs_truth"].is_object()) << t["technique"];
    // The decomposition's parts are over one set of pixels, the truth's, so RMSE being a norm
    // over them, the total is at most the sum of the parts (and each part at most the total
    // plus the other). Parts over different pixels need not obey it.
    const nlohmann::json& d = t["error_decomposition"];
    EXPECT_EQ(d["total_rmse_vs_truth"], t["vs_truth"]["rmse"]);
    EXPECT_EQ(d["sampling_rmse_reference_vs_truth"], truth["reference_vs_truth"]["rmse"]);
    EXPECT_EQ(d["pixels"], truth["pixels_measured"]);
    const double total = d["total_rmse_vs_truth"], sampling = d["sampling_rmse_reference_vs_truth"],
                 filtering = d["filtering_rmse_vs_reference"];
    EXPECT_LE(total, sampling + filtering + 1e-12) << t["technique"];
    EXPECT_LE(filtering, total + sampling + 1e-12) << t["technique"];
  }
  EXPECT_NE(r.html.find("Ranked by RMSE against the ray-traced truth"), std::string::npos);
  EXPECT_NE(r.html.find("RMSE truth"), std::string::npos);
  EXPECT_NE(r.csv.find("rmse_truth"), std::string::npos);
  EXPECT_TRUE(r.truthImages);
}

TEST(CompareTruth, NoneRanksByTheFilteredReferenceAsBefore) {
  const Report r = compare({"--truth", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(r.metrics["truth"].is_null());
  for (const nlohmann::json& t : r.metrics["techniques"]) EXPECT_TRUE(t["vs_truth"].is_null());
  EXPECT_NE(r.html.find("No ray-traced truth"), std::string::npos);
  EXPECT_NE(r.html.find("Ranked by RMSE against the filtered reference"), std::string::npos);
  EXPECT_FALSE(r.truthImages);
}

}  // namespace
}  // namespace penumbra::test
