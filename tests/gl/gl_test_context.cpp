// Context creation policy for GPU tests.
#include "gl_test_context.h"

#include <cstdlib>
#include <string>

#include "penumbra/error.h"

namespace penumbra::testing {

void GlTest::SetUp() {
  try {
    context = std::make_unique<gl::HeadlessContext>();
    RecordProperty("gl_device", context->description());
  } catch (const Error& e) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true") {
      FAIL() << "CI=true and no GL 4.5 context: " << e.what();
    }
    GTEST_SKIP() << "no GL 4.5 context on this machine: " << e.what();
  }
}

}  // namespace penumbra::testing
