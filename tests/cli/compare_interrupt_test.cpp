// A real `penumbra compare` child interrupted while its report is staged: SIGINT and SIGTERM
// remove the staging folder and leave the earlier report untouched; after SIGKILL, which
// cannot be handled, the next run to the same folder removes the leftover.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <thread>

#include "penumbra/compare/report_folder.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

// Long enough (all techniques, 8 frames: about 20 s on two cores) that the signal lands during
// the run, not after it.
const std::vector<std::string> kLongCompare{
    "compare", "--scene",       "backyard", "--technique", "all",   "--shadow-size",
    "512",     "--width",       "320",      "--height",    "180",   "--frames",
    "8",       "--supersample", "2",        "--quiet",     "--out", "report"};

// A report from an earlier run: the marker and a page.
void writeEarlierReport(const fs::path& target) {
  writeFile(target / std::string(compare::kReportMarkerFile),
            "penumbra report 1\nentry index.html\n");
  writeFile(target / "index.html", "earlier report");
}

// Waits until penumbra has created `path` (or gives up after 120 s).
bool waitFor(const fs::path& path, pid_t child) {
  for (int i = 0; i < 6000; ++i) {
    if (fs::exists(path)) return true;
    if (waitpid(child, nullptr, WNOHANG) != 0) return false;  // it ended early
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

fs::path stagingOf(const fs::path& folder, pid_t pid) {
  return folder / ("report.partial-" + std::to_string(pid));
}

// Waits until the staging folder carries its complete marker (or gives up after 120 s): the
// folder exists a moment before its marker, and a folder killed in that moment is not marked
// as penumbra's, so the next run rightly leaves it alone.
bool waitForStagingMarker(const fs::path& staging, pid_t child) {
  const fs::path marker = staging / std::string(compare::kReportMarkerFile);
  const std::string line = "staging " + std::to_string(child) + "\n";
  for (int i = 0; i < 6000; ++i) {
    if (readFile(marker).find(line) != std::string::npos) return true;
    if (waitpid(child, nullptr, WNOHANG) != 0) return false;  // it ended early
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

class CompareInterrupt : public testing::TestWithParam<int> {};

TEST_P(CompareInterrupt, RemovesTheStagingFolderAndKeepsTheEarlierReport) {
  const int signal = GetParam();
  ScratchFolder scratch;
  writeEarlierReport(scratch.path() / "report");
  const auto before = snapshot(scratch.path() / "report");
  const pid_t child = startPenumbra(kLongCompare, scratch.path(), scratch.path() / "log");
  ASSERT_TRUE(waitFor(stagingOf(scratch.path(), child), child)) << readFile(scratch.path() / "log");
  ASSERT_EQ(kill(child, signal), 0);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
      << "status " << status << "\n"
      << readFile(scratch.path() / "log");
  EXPECT_FALSE(fs::exists(stagingOf(scratch.path(), child)));
  EXPECT_EQ(entriesStartingWith(scratch.path(), "report.").size(), 0u);
  EXPECT_EQ(snapshot(scratch.path() / "report"), before);
}

INSTANTIATE_TEST_SUITE_P(Signals, CompareInterrupt, testing::Values(SIGINT, SIGTERM),
                         [](const testing::TestParamInfo<int>& signal) {
                           return std::string(signal.param == SIGINT ? "Sigint" : "Sigterm");
                         });

TEST(CompareKilled, TheNextRunRemovesTheLeftoverAndReplacesTheReport) {
  ScratchFolder scratch;
  writeEarlierReport(scratch.path() / "report");
  const pid_t child = startPenumbra(kLongCompare, scratch.path(), scratch.path() / "log");
  ASSERT_TRUE(waitForStagingMarker(stagingOf(scratch.path(), child), child));
  ASSERT_EQ(kill(child, SIGKILL), 0);
  waitpid(child, nullptr, 0);
  ASSERT_TRUE(fs::exists(stagingOf(scratch.path(), child)));  // SIGKILL leaves it behind
  EXPECT_EQ(readFile(scratch.path() / "report" / "index.html"), "earlier report");

  const RunResult next = runPenumbra(
      {"compare", "--scene", "planar", "--technique", "vsm", "--shadow-size", "64", "--width", "32",
       "--height", "32", "--frames", "2", "--supersample", "1", "--quiet", "--out", "report/"},
      scratch.path());
  EXPECT_EQ(next.exitCode(), 0) << next.output;
  EXPECT_FALSE(fs::exists(stagingOf(scratch.path(), child)));
  EXPECT_EQ(entriesStartingWith(scratch.path(), "report.").size(), 0u);
  EXPECT_NE(readFile(scratch.path() / "report" / "index.html"), "earlier report");
  EXPECT_TRUE(compare::isPenumbraReport(scratch.path() / "report"));
}

TEST(CompareOut, PathBelowAFileFailsWithOneLine) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "file", "text");
  const RunResult run = runPenumbra(
      {"compare", "--scene", "planar", "--technique", "vsm", "--shadow-size", "64", "--width", "32",
       "--height", "32", "--frames", "2", "--supersample", "1", "--quiet", "--out", "file/report"},
      scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_NE(run.output.find("cannot write the output next to"), std::string::npos) << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  EXPECT_EQ(readFile(scratch.path() / "file"), "text");
}

}  // namespace
}  // namespace penumbra::test
