// ProgramCache specialises a variant to the frame's technique only where its source reads it
// (TECHNIQUE_ID): the light pass compiles once for every technique, the encode once for each.
// On llvmpipe, a compare run with an empty shader cache compiled ten identical light passes.
#include "program_cache.h"

#include <gtest/gtest.h>

#include "gl_test_context.h"

namespace penumbra {
namespace {

class ProgramCacheTest : public testing::GlTest {};

TEST_F(ProgramCacheTest, OnlyVariantsThatReadTheTechniqueAreCompiledPerTechnique) {
  gl::ProgramCache programs;
  const std::vector<ShaderDefine> opaque{{"ALPHA_TEST", "0"}};
  const std::vector<ShaderDefine> encode{{"CHANNEL_FORMAT", "rg32f"},
                                         {"LAYER_COUNT", "1"},
                                         {"MSAA", "0"},
                                         {"ROWS_PER_INVOCATION", "4"}};
  programs.setTechnique(Technique::Vsm);
  const gl::Program& lightVsm =
      programs.graphics("passes/light_depth.vert", "passes/light_depth.frag", opaque);
  const gl::Program& encodeVsm = programs.compute("passes/encode.comp", encode);
  programs.setTechnique(Technique::Evsm2);
  const gl::Program& lightEvsm =
      programs.graphics("passes/light_depth.vert", "passes/light_depth.frag", opaque);
  const gl::Program& encodeEvsm = programs.compute("passes/encode.comp", encode);
  EXPECT_EQ(lightVsm.id(), lightEvsm.id()) << "the light pass reads no technique";
  EXPECT_NE(encodeVsm.id(), encodeEvsm.id()) << "the encode is the technique's";
}

// The shared constants (shared/constants.h) reach passes that read no technique, such as LVSM's
// Lloyd sums: they must not name the technique's define (PENUMBRA_COMPILES_TECHNIQUE's fallback
// lives there), or every such pass would compile once per technique.
TEST_F(ProgramCacheTest, PassesReadingOnlyTheSharedConstantsAreCompiledOnce) {
  gl::ProgramCache programs;
  programs.setTechnique(Technique::Lvsm);
  const gl::Program& lvsm = programs.compute("passes/lloyd_sums.comp", {});
  programs.setTechnique(Technique::PowerCdf);
  const gl::Program& powerCdf = programs.compute("passes/lloyd_sums.comp", {});
  EXPECT_EQ(lvsm.id(), powerCdf.id());
}

}  // namespace
}  // namespace penumbra
