// The shader loader: includes, #line mapping back to files, defines, and clear errors.
#include <gtest/gtest.h>

#include "penumbra/error.h"
#include "penumbra/shader_library.h"

namespace penumbra {
namespace {

std::string errorOf(const ShaderLibrary& library, std::string_view path) {
  try {
    library.expand(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ShaderLibrary, EmbedsEverySharedHeader) {
  const ShaderLibrary library;
  for (const char* header :
       {"shared/prelude.h", "shared/vsm.h", "shared/lvsm.h", "shared/evsm.h", "shared/esm.h",
        "shared/csm.h", "shared/power_cdf.h", "shared/msm.h", "shared/technique_dispatch.h"}) {
    EXPECT_TRUE(library.contains(header)) << header;
  }
}

TEST(ShaderLibrary, ResolvesIncludesAndEmitsVersionDefinesAndLines) {
  ShaderLibrary library;
  library.addFile("passes/a.comp", "// a\n#include \"../lib/b.glsl\"\nvoid main() {}\n");
  library.addFile("lib/b.glsl", "float b() { return 1.0f; }\n");
  const std::vector<ShaderDefine> defines{{"TECHNIQUE", "3"}};
  const ExpandedShader shader = library.expand("passes/a.comp", defines);
  EXPECT_EQ(shader.source.rfind("#version 450 core\n#define TECHNIQUE 3\n", 0), 0u);
  EXPECT_NE(shader.source.find("#line 1 1\nfloat b()"), std::string::npos);
  EXPECT_NE(shader.source.find("#line 3 0\nvoid main()"), std::string::npos);
  ASSERT_EQ(shader.files.size(), 2u);
  EXPECT_EQ(shader.files[1], "lib/b.glsl");
}

TEST(ShaderLibrary, TranslatesCompilerLocationsToFiles) {
  ShaderLibrary library;
  library.addFile("passes/a.comp", "#include \"../lib/b.glsl\"\n");
  library.addFile("lib/b.glsl", "x\n");
  const ExpandedShader shader = library.expand("passes/a.comp");
  EXPECT_EQ(shader.translateLog("1:7(12): error: bad"), "lib/b.glsl:7(12): error: bad");
  EXPECT_EQ(shader.translateLog("ERROR: 0:3: 'x' : undeclared"),
            "ERROR: passes/a.comp:3: 'x' : undeclared");
  EXPECT_EQ(shader.translateLog("1(4) : error C1008"), "lib/b.glsl:4 : error C1008");
}

TEST(ShaderLibrary, MissingIncludesNameTheIncluderAndLine) {
  ShaderLibrary library;
  library.addFile("passes/a.comp", "\n#include \"nope.h\"\n");
  EXPECT_NE(errorOf(library, "passes/a.comp").find("passes/a.comp:2: cannot find 'nope.h'"),
            std::string::npos);
  EXPECT_NE(errorOf(library, "passes/missing.comp").find("cannot find"), std::string::npos);
}

TEST(ShaderLibrary, RejectsVersionLinesAndIncludeCycles) {
  ShaderLibrary library;
  library.addFile("a.comp", "#version 430\n");
  EXPECT_NE(errorOf(library, "a.comp").find("belongs to the loader"), std::string::npos);
  library.addFile("x.h", "#include \"y.h\"\n");
  library.addFile("y.h", "#include \"x.h\"\n");
  EXPECT_NE(errorOf(library, "x.h").find("include cycle"), std::string::npos);
}

}  // namespace
}  // namespace penumbra
