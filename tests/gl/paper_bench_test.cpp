// penumbra bench --experiment: cases set against their baseline, memory ratios as the storage
// formats dictate, the kernel-scaling fit, and unknown experiments refused with the valid ids.
#include "penumbra/compare/paper_bench.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "gl_test_context.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

class PaperBench : public testing::GlTest {};

compare::BenchSizes tiny() {
  compare::BenchSizes z;
  z.shadowMapSize = 64;
  z.scalingShadowMapSize = 64;
  z.width = 32;
  z.height = 18;
  return z;
}

// A paper experiment at the tiny sizes, its cases up to x = maxX, one frame each.
compare::ExperimentResult runTinyExperiment(gl::Renderer& renderer, const std::string& id,
                                            double maxX) {
  compare::Experiment e = compare::makePaperExperiment(id, tiny());
  std::erase_if(e.cases, [maxX](const compare::BenchCase& c) { return c.x > maxX; });
  return compare::runPaperExperiment(renderer, makeBuiltinScene("planar"), e, 1);
}

TEST_F(PaperBench, GumbauCasesAreSetAgainstVsmWithTheirFormatsMemory) {
  gl::Renderer renderer(*context);
  const compare::Experiment e = compare::makePaperExperiment("gumbau-table1", tiny());
  const compare::ExperimentResult r =
      compare::runPaperExperiment(renderer, makeBuiltinScene("planar"), e, 2);
  ASSERT_EQ(r.cases.size(), 4u);
  // Channel texture per texel (the blur's scratch is not the technique's: it is absent when the
  // prefilter runs fused): VSM rg32f 8 bytes, ESM r32f 4, the power CDF's three channels rgba32f
  // 16 or rgba16f 8 (image formats have no RGB).
  const std::map<std::string, double> memory{
      {"VSM", 1.0}, {"ESM", 0.5}, {"power CDF, 32-bit", 2.0}, {"power CDF, 16-bit", 1.0}};
  for (const compare::CaseMeasurement& m : r.cases) {
    EXPECT_EQ(m.memoryRatio, memory.at(m.benchCase.series)) << m.benchCase.label;
    EXPECT_EQ(m.frameMs.size(), 2u);
    EXPECT_TRUE(m.medianMs > 0.0 && std::isfinite(m.medianMs)) << m.benchCase.label;
    EXPECT_TRUE(m.minMs <= m.medianMs && m.medianMs <= m.maxMs) << m.benchCase.label;
    if (m.benchCase.series == "VSM")
      EXPECT_EQ(m.timeRatio, 1.0);
    else
      EXPECT_NEAR(m.timeRatio, m.medianMs / r.cases[0].medianMs, 1e-12);
  }
}

// CSM's Table 1 against PCF: PCF keeps its R32F depth map (4 bytes a texel, no channel texture
// of its own), CSM M/2 RGBA8 layers with mips (trilinear, as the paper's anisotropic filtering):
// M = 4 is 2 layers x 4 bytes x 4/3 of PCF's texels (the mip chain of 64^2: 5461/4096).
TEST_F(PaperBench, CsmMemoryIsSetAgainstPcfsDepthMap) {
  gl::Renderer renderer(*context);
  const compare::ExperimentResult r = runTinyExperiment(renderer, "csm-table1", 1.0);
  const double mips = 5461.0 / 4096.0;
  const std::map<std::string, double> memory{
      {"PCF", 1.0}, {"CSM M=4", 2.0 * mips}, {"CSM M=8", 4.0 * mips}, {"CSM M=16", 8.0 * mips}};
  ASSERT_EQ(r.cases.size(), memory.size());
  for (const compare::CaseMeasurement& m : r.cases) {
    EXPECT_NEAR(m.memoryRatio, memory.at(m.benchCase.series), 1e-12) << m.benchCase.label;
  }
}

TEST_F(PaperBench, EachKernelIsSetAgainstTheBaselineOfTheSameKernel) {
  gl::Renderer renderer(*context);
  const compare::ExperimentResult r = runTinyExperiment(renderer, "esm-table1", 3.0);
  for (const compare::CaseMeasurement& m : r.cases) {
    const compare::CaseMeasurement* esm = nullptr;
    for (const compare::CaseMeasurement& b : r.cases) {
      if (b.benchCase.series == "ESM (threshold)" && b.benchCase.x == m.benchCase.x) esm = &b;
    }
    ASSERT_NE(esm, nullptr);
    EXPECT_NEAR(m.timeRatio, m.medianMs / esm->medianMs, 1e-12) << m.benchCase.label;
  }
}

TEST(PaperBenchFit, PowerLawWithAFixedCostIsRecovered) {
  const std::vector<double> k{3, 5, 7, 11, 15, 21, 31};
  std::vector<double> square, linear, pure;
  for (double x : k) {
    square.push_back(4.0 + 0.7 * x * x);  // PCF: a dispatch's fixed cost plus k^2 taps
    linear.push_back(40.0 + 2.5 * x);     // a blur pass's fixed cost plus 2k taps
    pure.push_back(1.5 * std::pow(x, 1.5));
  }
  // The exponent is found on a grid of 0.001; offset and scale are then exact least squares for
  // it, so they carry the exponent's rounding only (well within 1e-3 relative here).
  const compare::PowerLawFit s = compare::fitPowerLaw(k, square);
  EXPECT_NEAR(s.exponent, 2.0, 1e-9);
  EXPECT_NEAR(s.offset, 4.0, 1e-6);
  EXPECT_NEAR(s.scale, 0.7, 1e-9);
  const compare::PowerLawFit l = compare::fitPowerLaw(k, linear);
  EXPECT_NEAR(l.exponent, 1.0, 1e-9);
  EXPECT_NEAR(l.offset, 40.0, 1e-6);
  EXPECT_NEAR(compare::fitPowerLaw(k, pure).exponent, 1.5, 1e-9);
  EXPECT_THROW(compare::fitPowerLaw({3, 5}, {1, 2}), Error);
  EXPECT_THROW(compare::fitPowerLaw({3, 3, 3}, {1, 2, 3}), Error);
  EXPECT_THROW(compare::fitPowerLaw({3, 5, 7}, {1, NAN, 3}), Error);
}

TEST(PaperBenchIds, UnknownExperimentsListTheValidOnes) {
  try {
    compare::makePaperExperiment("esm-table9", {});
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "unknown experiment 'esm-table9'; valid experiments: esm-table1, csm-table1, "
                 "gumbau-table1, lvsm-layers, kernel-scaling");
  }
}

}  // namespace
}  // namespace penumbra
