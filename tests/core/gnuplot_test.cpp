// Text that reaches gnuplot is data: titles and paths holding backquotes, macros, quotes and line
// breaks are drawn or written as given and never run, and gnuplot runs without a shell from a
// private folder that it leaves behind empty-handed.
#include <gtest/gtest.h>
#include <pthread.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/gnuplot.h"
#include "penumbra/run_program.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "penumbra-gnuplot-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::vector<std::string> namesIn(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(Gnuplot, TextIsSingleQuotedWithQuotesDoubledAndControlCharactersReplaced) {
  EXPECT_EQ(gnuplotText("it's `date`"), "'it''s `date`'");
  EXPECT_EQ(gnuplotText("a\nb\rc\td"), "'a?b?c?d'");
}

TEST(Gnuplot, PathIsAbsoluteSoItCannotNameAPipe) {
  // gnuplot's `set output '|cmd'` and `plot '<cmd'` run commands; an absolute path starts '/'.
  const std::string quoted = gnuplotPath("|touch x");
  EXPECT_EQ(quoted.substr(0, 2), "'/") << quoted;
  EXPECT_NE(quoted.find("|touch x'"), std::string::npos) << quoted;
}

TEST(Gnuplot, PathWithALineBreakIsRefused) {
  EXPECT_THROW(gnuplotPath("plot\nsystem('touch x')"), Error);
}

// Every construct that made gnuplot run a command before: backquotes and macros in titles and in
// the output file's name, a quote closing the literal early, a line break starting a new command.
TEST(Gnuplot, HostileTitlesAndFileNamesAreNeverRun) {
  ScratchFolder scratch;
  // gnuplot runs in the scratch folder, so a relative `touch PWNED` would land there.
  struct InFolder {
    fs::path previous = fs::current_path();
    explicit InFolder(const fs::path& folder) { fs::current_path(folder); }
    ~InFolder() { fs::current_path(previous); }
  } inScratch(scratch.path());
  const fs::path victim = scratch.path() / "PWNED";
  const std::string touch = "touch " + victim.string();
  const fs::path out = scratch.path() / "plot`touch PWNED`$(touch PWNED).txt";
  const std::vector<std::string> titles{"t`" + touch + "`", "t\" . system('" + touch + "') . \"",
                                        "t' . system('" + touch + "') . '",
                                        "t\nsystem('" + touch + "')"};
  for (const std::string& title : titles) {
    std::ostringstream script;
    script << "x = 'system(\"" << touch << "\")'\n"
           << "set terminal dumb size 300,12\nset output " << gnuplotPath(out) << "\n"
           << "set title " << gnuplotText(title) << " noenhanced\nplot x*x notitle\n";
    GnuplotRun(scratch.path()).run(script.str());
    EXPECT_FALSE(fs::exists(victim)) << "ran a command from the title " << title;
    // The title made it through as text (its line breaks as '?').
    std::ifstream in(out);
    const std::string drawn{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::string expected = title;
    std::replace(expected.begin(), expected.end(), '\n', '?');
    EXPECT_NE(drawn.find(expected), std::string::npos) << drawn;
  }
  // Only the plot itself is left: the script, the log and the private folder are gone.
  EXPECT_EQ(namesIn(scratch.path()), std::vector<std::string>{out.filename().string()});
}

TEST(Gnuplot, FailureCarriesGnuplotsMessageAndLeavesNothing) {
  ScratchFolder scratch;
  try {
    GnuplotRun(scratch.path()).run("plot no_such_function(x)\n");
    FAIL() << "an invalid script ran";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot failed:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no_such_function"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(namesIn(scratch.path()).empty());
}

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A report queues its figures into one run: each figure is drawn to its own file, starts from
// gnuplot's defaults (the first's title must not reach the second, drawn by the same process),
// and a failing figure leaves the ones before it complete.
TEST(Gnuplot, FiguresQueuedInOneRunAreDrawnApart) {
  ScratchFolder scratch;
  const fs::path first = scratch.path() / "first.txt", second = scratch.path() / "second.txt";
  {
    GnuplotRun run(scratch.path(), 1);
    run.add("set terminal dumb size 300,12\nset output " + gnuplotPath(first) +
            "\nset title 'FIRSTTITLE'\nplot x notitle\n");
    run.add("set terminal dumb size 300,12\nset output " + gnuplotPath(second) +
            "\nplot x*x notitle\n");
    EXPECT_EQ(run.figureCount(), 2);
    run.run();
  }
  EXPECT_NE(readText(first).find("FIRSTTITLE"), std::string::npos);
  EXPECT_FALSE(readText(second).empty());
  EXPECT_EQ(readText(second).find("FIRSTTITLE"), std::string::npos)
      << "a setting of one figure leaked into the next";

  const fs::path third = scratch.path() / "third.txt";
  GnuplotRun failing(scratch.path(), 1);
  failing.add("set terminal dumb size 300,12\nset output " + gnuplotPath(third) +
              "\nset title 'THIRDTITLE'\nplot x notitle\n");
  failing.add("plot no_such_function(x)\n");
  EXPECT_THROW(failing.run(), Error);
  EXPECT_NE(readText(third).find("THIRDTITLE"), std::string::npos)
      << "the figure before a failing one was not finished";
}

// Figures spread over several processes: every figure is drawn, and one process's failure is
// reported after the others have drawn theirs. Each figure says whether it is its process's first
// (a user variable survives `reset`, so a process's later figures see it): three processes for
// three or more figures, each process's first titled FIRST.
TEST(Gnuplot, FiguresSpreadOverProcessesAreAllDrawn) {
  ScratchFolder scratch;
  auto figure = [&](const std::string& name, const std::string& title) {
    return "set terminal dumb size 300,12\nset output " + gnuplotPath(scratch.path() / name) +
           "\nif (exists('drawnBefore')) { set title '" + title + " LATER' } else { set title '" +
           title + " FIRST' }\ndrawnBefore = 1\nplot x notitle\n";
  };
  {
    GnuplotRun run(scratch.path(), 3);
    run.add(figure("big.txt", "BIG"), 100.0);
    for (int i = 0; i < 4; ++i) run.add(figure("small" + std::to_string(i) + ".txt", "SMALL"));
    run.add("plot no_such_function(x)\n");
    try {
      run.run();
      FAIL() << "a failing figure went unreported";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("no_such_function"), std::string::npos) << e.what();
    }
  }
  EXPECT_NE(readText(scratch.path() / "big.txt").find("BIG FIRST"), std::string::npos)
      << "the big figure shares a process";
  int firsts = 0;
  for (int i = 0; i < 4; ++i) {
    const std::string text = readText(scratch.path() / ("small" + std::to_string(i) + ".txt"));
    EXPECT_NE(text.find("SMALL"), std::string::npos) << "small figure " << i;
    firsts += text.find("SMALL FIRST") != std::string::npos ? 1 : 0;
  }
  EXPECT_EQ(firsts, 2) << "the small figures were not drawn by the two other processes";
  // Only the figures are left: scripts, logs and the private folder are gone.
  EXPECT_EQ(namesIn(scratch.path()).size(), 5u);
}

// A run whose gnuplot cannot start says so and leaves nothing queued behind it: the same run
// draws again once gnuplot is found.
TEST(Gnuplot, ARunThatCouldNotStartGnuplotCanDrawAgain) {
  ScratchFolder scratch;
  const fs::path out = scratch.path() / "again.txt";
  const std::string figure = "set terminal dumb size 300,12\nset output " + gnuplotPath(out) +
                             "\nset title 'AGAIN'\nplot x notitle\n";
  GnuplotRun run(scratch.path(), 2);
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", scratch.path().c_str(), 1);  // a folder without gnuplot
  run.add(figure);
  run.add(figure);
  try {
    run.run();
    ADD_FAILURE() << "a run without gnuplot succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not installed"), std::string::npos) << e.what();
  }
  ::setenv("PATH", path.c_str(), 1);
  run.add(figure);  // two processes again: neither may find its script from the failed run
  run.run(figure);
  EXPECT_NE(readText(out).find("AGAIN"), std::string::npos);
}

TEST(Gnuplot, ScratchFilesStayInThePrivateFolder) {
  ScratchFolder scratch;
  {
    GnuplotRun run(scratch.path());
    const fs::path data = run.scratchFile("points.dat");
    EXPECT_EQ(data.parent_path().parent_path(), scratch.path());
    EXPECT_EQ(fs::status(data.parent_path()).permissions() & fs::perms::all, fs::perms::owner_all);
    EXPECT_THROW(run.scratchFile("../escape.dat"), Error);
    EXPECT_THROW(run.scratchFile(".."), Error);
  }
  EXPECT_TRUE(namesIn(scratch.path()).empty());
}

TEST(RunProgram, ArgumentsReachTheProgramUnparsed) {
  ScratchFolder scratch;
  const fs::path log = scratch.path() / "log";
  const std::string hostile = "a b;touch " + (scratch.path() / "PWNED").string() + "`x`$(y)'\"";
  const ProgramResult result = runProgram({"printf", "%s", hostile}, log);
  EXPECT_TRUE(result.succeeded());
  std::ifstream in(log);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()),
            hostile);
  EXPECT_FALSE(fs::exists(scratch.path() / "PWNED"));
}

// The CLI blocks SIGINT and SIGTERM in every thread for its interrupt watcher: a child must not
// inherit that (it would outlive a Ctrl-C), nor read the terminal (a background run would stop).
TEST(RunProgram, TheChildHasNoBlockedSignalsAndNoInput) {
  ScratchFolder scratch;
  sigset_t interrupts, previous;
  sigemptyset(&interrupts);
  sigaddset(&interrupts, SIGINT);
  sigaddset(&interrupts, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &interrupts, &previous);
  const ProgramResult status =
      runProgram({"grep", "^SigBlk", "/proc/self/status"}, scratch.path() / "status");
  const ProgramResult input = runProgram({"readlink", "/proc/self/fd/0"}, scratch.path() / "fd0");
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  ASSERT_TRUE(status.succeeded() && input.succeeded());
  std::ifstream statusText(scratch.path() / "status"), inputText(scratch.path() / "fd0");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(statusText), {}),
            "SigBlk:\t0000000000000000\n");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(inputText), {}), "/dev/null\n");
}

TEST(RunProgram, AMissingProgramIsReportedAsNotStarted) {
  const ProgramResult result = runProgram({"penumbra-no-such-program-xyz"});
  EXPECT_FALSE(result.started);
  EXPECT_FALSE(result.succeeded());
}

TEST(RunProgram, ExitStatusIsReported) {
  EXPECT_EQ(runProgram({"false"}).exitCode, 1);
  EXPECT_TRUE(runProgram({"true"}).succeeded());
}

// A log path where someone planted a link to a file of theirs: refused, the file untouched.
TEST(RunProgram, APlantedLinkAtTheLogIsNeverWrittenThrough) {
  ScratchFolder scratch;
  const fs::path victim = scratch.path() / "victim.txt";
  std::ofstream(victim) << "precious";
  fs::create_symlink(victim, scratch.path() / "log");
  EXPECT_THROW(runProgram({"echo", "overwritten"}, scratch.path() / "log"), Error);
  std::ifstream in(victim);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()),
            "precious");
}

}  // namespace
}  // namespace penumbra
