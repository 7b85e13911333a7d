// `compare` never overrides a PCF setting the user made: PCF is matched to the prefilter only when
// the user set none of its parameters, then with the blur's whole kernel (no clamped radius, any
// sigma the blur takes), and the report says which it was.
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
};

Report compare(const std::vector<std::string>& extra) {
  ScratchFolder scratch;
  std::vector<std::string> args{
      "compare", "--scene",  "planar", "--shadow-size", "128", "--width", "64",    "--height",
      "36",      "--frames", "2",      "--supersample", "1",   "--quiet", "--out", "report"};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult run = runPenumbra(args, scratch.path());
  Report report{run.exitCode(), run.output, {}, {}};
  if (run.exitCode() == 0) {
    report.metrics = nlohmann::json::parse(readFile(scratch.path() / "report" / "metrics.json"));
    report.html = readFile(scratch.path() / "report" / "index.html");
  }
  return report;
}

const nlohmann::json& technique(const Report& r, const std::string& id) {
  for (const nlohmann::json& t : r.metrics["techniques"]) {
    if (t["technique"] == id) return t;
  }
  throw std::runtime_error("no " + id + " in the report");
}

TEST(ComparePcf, MatchesABlurWiderThan31TapsAndASigmaAbove16) {
  // 41 taps, sigma 20: PCF once had its radius clamped to 15 and failed on sigma > 16.
  const Report r = compare({"--technique", "vsm,pcf", "--filter", "point", "--blur-kernel",
                            "gaussian", "--blur", "41", "--blur-sigma", "20"});
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json& pcf = technique(r, "pcf");
  EXPECT_EQ(pcf["params"]["kernel"], "gaussian");
  EXPECT_EQ(pcf["params"]["radius"], "20");
  EXPECT_EQ(pcf["params"]["sigma"], "20");
  EXPECT_EQ(r.metrics["settings"]["pcf_kernel_matched_to_prefilter"], true);
  // With point lookups matched PCF is the filtered reference (fp32 summation apart).
  EXPECT_LT(pcf["vs_filtered_reference"]["max_absolute"].get<double>(), 1e-5);
  EXPECT_NE(r.html.find("runs with the prefilter's kernel"), std::string::npos);
}

TEST(ComparePcf, AnyPcfParameterTheUserSetsIsKeptAndTheReportSaysPcfIsNotMatched) {
  // Unqualified, constantBias reaches both hard and PCF; qualified, pcf.sigma reaches PCF only.
  for (const std::vector<std::string>& params :
       {std::vector<std::string>{"--param", "constantBias=0.01"},
        std::vector<std::string>{"--param", "pcf.sigma=2"}}) {
    std::vector<std::string> extra{"--technique", "hard,pcf", "--blur", "9", "--blur-sigma", "30"};
    extra.insert(extra.end(), params.begin(), params.end());
    const Report r = compare(extra);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json& pcf = technique(r, "pcf")["params"];
    const bool bias = params[1] == "constantBias=0.01";
    EXPECT_EQ(pcf["constantBias"], bias ? "0.01" : "0.0005")
        << params[1];                                        // the user's or PCF's own
    EXPECT_EQ(pcf["sigma"], bias ? "1" : "2") << params[1];  // not the blur's 30
    EXPECT_EQ(pcf["radius"], "2") << params[1];              // PCF's default, not the blur's 4
    EXPECT_EQ(pcf["kernel"], "bilinear") << params[1];
    EXPECT_EQ(r.metrics["settings"]["pcf_kernel_matched_to_prefilter"], false);
    EXPECT_NE(r.html.find("PCF is not matched to the prefilter"), std::string::npos);
  }
}

TEST(ComparePcf, ParametersOfOtherTechniquesKeepPcfMatched) {
  const Report r =
      compare({"--technique", "vsm,pcf", "--param", "bleedReduction=0.2", "--blur", "7"});
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.metrics["settings"]["pcf_kernel_matched_to_prefilter"], true);
  EXPECT_EQ(technique(r, "pcf")["params"]["radius"], "3");
}

}  // namespace
}  // namespace penumbra::test
