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
    std::vector<std::string> extra{"--technique", "hard,pcf",     "--blur",       "9",
                                   "--blur-kernel", "gaussian", "--blur-sigma", "30"};
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

TEST(ComparePcf, PcfParametersFromASettingsFileAreKeptAsGiven) {
  // The viewer saves every parameter of each technique it lists; compare once replaced the file's
  // PCF parameters with the matched kernel and said nothing.
  ScratchFolder files;
  const fs::path settings = files.path() / "settings.json";
  writeFile(settings, R"({"technique": "vsm,pcf", "blur": 7, "param": {"pcf": {"kernel": "box",
            "radius": 1, "constantBias": 0.002}}})");
  const Report r = compare({"--settings", settings.string()});
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json& pcf = technique(r, "pcf")["params"];
  EXPECT_EQ(pcf["kernel"], "box");  // matched: "bilinear", the blur's radius 3, bias 2e-5
  EXPECT_EQ(pcf["radius"], "1");
  EXPECT_EQ(pcf["constantBias"], "0.002");
  EXPECT_EQ(r.metrics["settings"]["pcf_kernel_matched_to_prefilter"], false);
  EXPECT_NE(r.html.find("PCF is not matched to the prefilter"), std::string::npos);
}

TEST(ComparePcf, UnderMsaaTheReportSaysSoAndMatchedPcfIsNotCalledTheReference) {
  // The techniques' light pass is multisampled, the references' is not: matched PCF tests the
  // nearest sample and so differs from the reference on silhouettes.
  const Report r = compare({"--technique", "vsm,pcf", "--msaa", "4", "--filter", "bilinear"});
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.metrics["settings"]["msaa_samples"], 4);
  const std::string msaa = r.metrics["references"]["msaa"];
  EXPECT_NE(msaa.find("4x MSAA"), std::string::npos) << msaa;
  EXPECT_NE(msaa.find("single-sampled"), std::string::npos) << msaa;
  EXPECT_NE(r.html.find("4× MSAA"), std::string::npos);
  EXPECT_EQ(r.html.find("filtered reference itself"), std::string::npos);
  EXPECT_NE(r.html.find("it is not the reference"), std::string::npos);
}

TEST(ComparePcf, WithoutMsaaMatchedPcfIsTheReferenceAndTheLightIsNotCalledAPointLight) {
  const Report r = compare({"--technique", "vsm,pcf", "--filter", "bilinear"});
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.html.find("filtered reference itself"), std::string::npos);
  EXPECT_EQ(r.html.find("MSAA"), std::string::npos);
  // planar's light is directional and has no size.
  const std::string areaLight = r.metrics["references"]["area_light"];
  EXPECT_EQ(areaLight.find("point light"), std::string::npos) << areaLight;
  EXPECT_NE(areaLight.find("no size"), std::string::npos) << areaLight;
}

}  // namespace
}  // namespace penumbra::test
