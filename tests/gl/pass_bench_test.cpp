// bench --passes: every prefilter pass of a filtered technique is measured beside its minimal
// kernel; techniques without a prefilter are refused.
#include "penumbra/gl/pass_bench.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST_F(PassBench, MeasuresEveryPrefilterPassBesideItsMinimalKernel) {
  gl::Renderer renderer(*context);
  const gl::PassBenchResult r =
      gl::benchPasses(renderer, makeBuiltinScene("planar"), small(Technique::Evsm4), 2);
  EXPECT_EQ(r.format, "rgba32f x 1 layer");
  ASSERT_EQ(r.passes.size(), 3u);  // trilinear: encode, prefilter and mips
  const char* passes[] = {"encode", "prefilter", "mips"};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r.passes[i].pass, passes[i]);
    EXPECT_TRUE(r.passes[i].passMs > 0.0 && std::isfinite(r.passes[i].passMs));
    EXPECT_TRUE(r.passes[i].baselineMs > 0.0 && std::isfinite(r.passes[i].baselineMs));
  }
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
