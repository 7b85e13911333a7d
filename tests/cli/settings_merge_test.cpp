// A settings file and the command line merged: an option given on the command line is the
// value used, whatever order the file's keys take effect in.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "run_penumbra.h"

namespace penumbra::test {
namespace {

// The file's "blur" sets its width's default sigma; a --blur-sigma given with the file stayed
// overridden by it (the viewer saves "blur" in every file).
TEST(SettingsMerge, ABlurSigmaOnTheCommandLineOutlivesTheFilesBlurWidth) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "s.json",
            R"({"technique":"vsm","blur":5,"blur-kernel":"gaussian","blur-sigma":1})");
  const RunResult run = runPenumbra(
      {"render", "--scene", "planar", "--settings", "s.json", "--blur-sigma", "3",
       "--shadow-size", "128", "--width", "64", "--height", "36", "--out", "out"},
      scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const nlohmann::json record =
      nlohmann::json::parse(readFile(scratch.path() / "out" / "planar_vsm.json"));
  EXPECT_EQ(record["settings"]["blur"]["taps"], 5);
  EXPECT_FLOAT_EQ(record["settings"]["blur"]["sigma"].get<float>(), 3.0f);
}

}  // namespace
}  // namespace penumbra::test
