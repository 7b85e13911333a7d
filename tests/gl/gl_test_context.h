// GPU test fixture: a headless GL 4.5 context, or a skip where none can be made outside CI.
// With CI=true a missing context fails the test: GPU tests must run there (llvmpipe).
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "penumbra/gl/context.h"

namespace penumbra::testing {

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override;
  std::unique_ptr<gl::HeadlessContext> context;
};

}  // namespace penumbra::testing
