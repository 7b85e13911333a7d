// The commands' --out as a user would get it wrong: the current folder, a trailing slash on a
// folder of theirs, an empty path. Each is refused with one line before any GL work, and
// nothing in the user's folders changes.
#include <gtest/gtest.h>

#include "run_penumbra.h"

namespace penumbra::test {
namespace {

const std::vector<std::string> kSmallCompare{"compare", "--scene",  "planar", "--technique",
                                             "vsm",     "--frames", "2",      "--supersample",
                                             "1",       "--quiet"};

std::vector<std::string> compareTo(const std::string& out) {
  std::vector<std::string> args = kSmallCompare;
  args.insert(args.end(), {"--out", out});
  return args;
}

bool lineCount(const std::string& text, size_t lines) {
  return size_t(std::count(text.begin(), text.end(), '\n')) == lines;
}

TEST(CompareOut, CurrentFolderIsRefusedAndLeftUntouched) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "work" / "thesis.tex", "mine");
  writeFile(scratch.path() / "work" / "data" / "run.csv", "1,2");
  const auto before = snapshot(scratch.path());
  const RunResult run = runPenumbra(compareTo("."), scratch.path() / "work");
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_NE(run.output.find("is the current folder or contains it"), std::string::npos)
      << run.output;
  EXPECT_TRUE(lineCount(run.output, 1)) << run.output;
  EXPECT_EQ(snapshot(scratch.path()), before);
}

TEST(CompareOut, FolderOfTheUserWithATrailingSlashIsRefused) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "c" / "photo.jpg", "jpeg");
  const auto before = snapshot(scratch.path());
  for (const char* out : {"c/", "c"}) {
    const RunResult run = runPenumbra(compareTo(out), scratch.path());
    EXPECT_EQ(run.exitCode(), 1) << run.output;
    EXPECT_NE(run.output.find("is not a penumbra report"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("--force"), std::string::npos) << run.output;
  }
  EXPECT_EQ(snapshot(scratch.path()), before);
}

TEST(CompareOut, EmptyPathIsRefused) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "keep.txt", "mine");
  const RunResult run = runPenumbra(compareTo(""), scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_NE(run.output.find("path is empty"), std::string::npos) << run.output;
  EXPECT_EQ(snapshot(scratch.path()).size(), 1u);
}

TEST(CurvesOut, EmptyPathIsRefused) {
  ScratchFolder scratch;
  const RunResult run = runPenumbra({"curves", "--no-plot", "--out", ""}, scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_NE(run.output.find("output folder path is empty"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(scratch.path() / "curves.csv"));
}

TEST(CurvesOut, WritesIntoAnExistingFolderAndDeletesNothing) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "c" / "photo.jpg", "jpeg");
  const RunResult run = runPenumbra({"curves", "--no-plot", "--out", "c/"}, scratch.path());
  EXPECT_EQ(run.exitCode(), 0) << run.output;
  EXPECT_EQ(readFile(scratch.path() / "c" / "photo.jpg"), "jpeg");
  EXPECT_TRUE(fs::exists(scratch.path() / "c" / "curves.csv"));
}

TEST(RenderOut, EmptyPathIsRefused) {
  ScratchFolder scratch;
  const RunResult run = runPenumbra({"render", "--out", ""}, scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_NE(run.output.find("output folder path is empty"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace penumbra::test
