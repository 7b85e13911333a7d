// bench --passes: every prefilter pass of a filtered technique is measured beside its minimal
// kernel; techniques without a prefilter are refused.
#include "penumbra/gl/pass_bench.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gl_test_context.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

class PassBench : public testing::GlTest {};

gl::RenderSettings small(Technique technique) {
  gl::RenderSettings s;
  s.technique = technique;
  s.shadowMapSize = 128;
  s.width = 32;
  s.height = 18;
  return s;
}

void expectTimed(const gl::PassBenchResult& r, const std::vector<std::string>& passes) {
  ASSERT_EQ(r.passes.size(), passes.size());
  for (size_t i = 0; i < passes.size(); ++i) {
    EXPECT_EQ(r.passes[i].pass, passes[i]);
    EXPECT_TRUE(r.passes[i].passMs > 0.0 && std::isfinite(r.passes[i].passMs)) << passes[i];
    EXPECT_TRUE(r.passes[i].baselineMs > 0.0 && std::isfinite(r.passes[i].baselineMs)) << passes[i];
  }
}

TEST_F(PassBench, MeasuresEveryPrefilterPassBesideItsMinimalKernel) {
  gl::Renderer renderer(*context);
  // RGBA32F: the separate passes, and the fused one beside both their minimal kernels.
  const gl::PassBenchResult evsm =
      gl::benchPasses(renderer, makeBuiltinScene("planar"), small(Technique::Evsm4), 2);
  EXPECT_EQ(evsm.format, "rgba32f x 1 layer");
  EXPECT_EQ(evsm.timing, gl::passTimingDescription(renderer));
  expectTimed(evsm, {"encode", "prefilter", "mips", "encode + prefilter, fused"});
  // The yardstick (rawblur's kernels on a 2D texture of the same components) beside the encode,
  // the blur and the fused pass; the mips have none.
  const std::vector<std::string> yardsticks{"rawblur copy, rgba32f",
                                            "rawblur blur, 5 taps, rgba32f", "",
                                            "rawblur copy + blur, 5 taps, rgba32f"};
  for (size_t i = 0; i < yardsticks.size(); ++i) {
    EXPECT_EQ(evsm.passes[i].yardstick, yardsticks[i]);
    EXPECT_EQ(evsm.passes[i].yardstickMs > 0.0, !yardsticks[i].empty()) << evsm.passes[i].pass;
    EXPECT_TRUE(std::isfinite(evsm.passes[i].yardstickMs)) << evsm.passes[i].pass;
  }
  // 16-bit storage rounds the blur's intermediate: no fused pass.
  expectTimed(gl::benchPasses(renderer, makeBuiltinScene("planar"), small(Technique::Msm), 1),
              {"encode", "prefilter", "mips"});
  // The summed-area filter: encode and the table, no blur.
  gl::RenderSettings sat = small(Technique::Vsm);
  sat.filter = gl::FilterMode::SummedArea;
  expectTimed(gl::benchPasses(renderer, makeBuiltinScene("planar"), sat, 1),
              {"encode", "summed-area table"});
}

TEST_F(PassBench, TechniquesWithoutAPrefilterAreRefused) {
  gl::Renderer renderer(*context);
  for (Technique t : {Technique::Pcf, Technique::Hard}) {
    try {
      gl::benchPasses(renderer, makeBuiltinScene("planar"), small(t), 1);
      ADD_FAILURE() << techniqueId(t) << " must be refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("no prefilter"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace penumbra
