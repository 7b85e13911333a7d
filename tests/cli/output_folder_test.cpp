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
  EXPECT_NE(run.output.find("path is empty"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(scratch.path() / "curves.csv"));
}

TEST(CurvesOut, AFolderOfTheUserIsRefusedAndLeftUntouched) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "c" / "photo.jpg", "jpeg");
  const auto before = snapshot(scratch.path());
  const RunResult run = runPenumbra({"curves", "--no-plot", "--out", "c/"}, scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_NE(run.output.find("is not a penumbra report"), std::string::npos) << run.output;
  EXPECT_TRUE(lineCount(run.output, 1)) << run.output;
  EXPECT_EQ(snapshot(scratch.path()), before);
}

TEST(CurvesOut, AnEarlierOutputIsReplacedWhole) {
  ScratchFolder scratch;
  ASSERT_EQ(runPenumbra({"curves", "--out", "c"}, scratch.path()).exitCode(), 0);
  ASSERT_TRUE(fs::exists(scratch.path() / "c" / "curves.png"));
  const RunResult run = runPenumbra({"curves", "--no-plot", "--out", "c"}, scratch.path());
  EXPECT_EQ(run.exitCode(), 0) << run.output;
  EXPECT_TRUE(fs::exists(scratch.path() / "c" / "curves.csv"));
  EXPECT_FALSE(fs::exists(scratch.path() / "c" / "curves.png")) << "a stale plot was kept";
}

// Every subcommand that writes a folder refuses the root, the current folder and a folder of the
// user's before it does any work, and leaves them as they were.
TEST(EveryCommandOut, RootCurrentAndForeignFoldersAreRefused) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "work" / "index.html", "mine");
  writeFile(scratch.path() / "mine" / "index.html", "mine");
  writeFile(scratch.path() / "mine" / "plots" / "sweep.png.dat", "mine too");
  const auto before = snapshot(scratch.path());
  const std::vector<std::vector<std::string>> commands{
      {"render", "--scene", "planar"},
      {"curves", "--no-plot"},
      {"bench", "--passes", "--scene", "planar", "--technique", "vsm"},
      {"bench", "--experiment", "kernel-scaling", "--scene", "planar"},
      {"figures"},
      {"compare", "--scene", "planar", "--technique", "vsm"}};
  const std::vector<std::pair<std::string, std::string>> outs{
      {"/", "file-system root"},
      {".", "is the current folder or contains it"},
      {"..", "is the current folder or contains it"},
      {"../mine/", "is not a penumbra report"}};
  for (const std::vector<std::string>& command : commands) {
    for (const auto& [out, expected] : outs) {
      std::vector<std::string> args = command;
      args.insert(args.end(), {"--out", out});
      const RunResult run = runPenumbra(args, scratch.path() / "work");
      EXPECT_EQ(run.exitCode(), 1) << command[0] << " --out " << out << ": " << run.output;
      EXPECT_NE(run.output.find(expected), std::string::npos)
          << command[0] << " --out " << out << ": " << run.output;
    }
  }
  EXPECT_EQ(snapshot(scratch.path()), before);
}

// Names and TMPDIR values that ran commands through gnuplot's backquotes and the shell that
// started it (issue 23): the plot is written under the literal name, nothing runs, TMPDIR is
// not used at all (no file there, the file before the space untouched), no scratch file is left.
TEST(CurvesOut, HostileNamesAndTmpdirRunNothingAndLeaveNothing) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "x" / "my", "unrelated");
  fs::create_directories(scratch.path() / "x" / "my dir");
  fs::create_directories(scratch.path() / "t;touch PWNED4;");
  const std::string out = "c`touch PWNED3`$(touch PWNED5)";
  for (const std::string& tmpdir :
       {(scratch.path() / "x" / "my dir").string(), std::string("t;touch PWNED4;")}) {
    const RunResult run = runPenumbra({"curves", "--out", out}, scratch.path(), {{"TMPDIR", tmpdir}});
    EXPECT_EQ(run.exitCode(), 0) << run.output;
  }
  EXPECT_TRUE(fs::exists(scratch.path() / out / "curves.png"));
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(scratch.path())) {
    names.push_back(fs::relative(entry.path(), scratch.path()).string());
  }
  std::sort(names.begin(), names.end());
  const std::vector<std::string> expected{out,
                                          out + "/.penumbra-report",
                                          out + "/curves.csv",
                                          out + "/curves.png",
                                          "t;touch PWNED4;",
                                          "x",
                                          "x/my",
                                          "x/my dir"};
  EXPECT_EQ(names, expected);
  EXPECT_EQ(readFile(scratch.path() / "x" / "my"), "unrelated");
}

TEST(RenderOut, EmptyPathIsRefused) {
  ScratchFolder scratch;
  const RunResult run = runPenumbra({"render", "--out", ""}, scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_NE(run.output.find("path is empty"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace penumbra::test
