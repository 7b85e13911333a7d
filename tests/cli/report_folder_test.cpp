// The report folder never deletes what penumbra did not write: targets are checked before
// anything is created, a report is staged beside its target and swapped in complete, and
// leftovers of dead runs are removed only when they carry penumbra's marker.
#include "penumbra/compare/report_folder.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "penumbra/error.h"
#include "penumbra/output_journal.h"
#include "penumbra/text_file.h"
#include "run_penumbra.h"

namespace penumbra::compare {
namespace {

namespace fs = std::filesystem;
using test::entriesStartingWith;
using test::readFile;
using test::ScratchFolder;
using test::snapshot;
using test::writeFile;

std::string errorOf(auto&& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Runs the test body with `folder` as the current folder.
class InFolder {
 public:
  explicit InFolder(const fs::path& folder) : previous_(fs::current_path()) {
    fs::current_path(folder);
  }
  ~InFolder() { fs::current_path(previous_); }

 private:
  fs::path previous_;
};

// A complete report at `target` holding `note`.
void writeReport(const fs::path& target, const std::string& note) {
  ReportFolder folder(target, false);
  folder.createStaging();
  writeFile(folder.staging() / "index.html", note);
  folder.commit();
}

// A process id that is certainly not running: a child that has exited and been reaped.
long deadPid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  waitpid(pid, nullptr, 0);
  return long(pid);
}

TEST(ReportFolder, RefusesAnEmptyPath) {
  EXPECT_NE(errorOf([] { ReportFolder("", false); }).find("path is empty"), std::string::npos);
}

TEST(ReportFolder, RefusesTheCurrentFolderAndFoldersContainingIt) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "work" / "notes.txt", "mine");
  InFolder here(scratch.path() / "work");
  for (const char* out : {".", "./", "..", "../work", "/"}) {
    const std::string message = errorOf([&] { ReportFolder(out, true); });
    EXPECT_TRUE(message.find("current folder") != std::string::npos ||
                message.find("file-system root") != std::string::npos)
        << out << ": " << message;
  }
  EXPECT_EQ(readFile(scratch.path() / "work" / "notes.txt"), "mine");
}

TEST(ReportFolder, TrailingSeparatorNamesTheSameFolder) {
  ScratchFolder scratch;
  InFolder here(scratch.path());
  EXPECT_EQ(ReportFolder("report/", false).target(), ReportFolder("report", false).target());
  EXPECT_EQ(ReportFolder("report/", false).target().filename(), "report");
}

TEST(ReportFolder, RefusesAnExistingFolderThatIsNotAReportAndLeavesItAlone) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "photos" / "holiday.jpg", "jpeg");
  const auto before = snapshot(scratch.path());
  for (const fs::path& out : {scratch.path() / "photos", scratch.path() / "photos/"}) {
    const std::string message = errorOf([&] { ReportFolder(out, false); });
    EXPECT_NE(message.find("is not a penumbra report"), std::string::npos) << message;
    EXPECT_NE(message.find("--force"), std::string::npos) << message;
  }
  EXPECT_EQ(snapshot(scratch.path()), before);
}

TEST(ReportFolder, RefusesAFileAndASymbolicLink) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "file", "text");
  writeReport(scratch.path() / "report", "old");
  fs::create_directory_symlink(scratch.path() / "report", scratch.path() / "link");
  EXPECT_NE(errorOf([&] { ReportFolder(scratch.path() / "file", true); }).find("is not a folder"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { ReportFolder(scratch.path() / "link", true); }).find("symbolic link"),
            std::string::npos);
}

TEST(ReportFolder, ReplacesAnEarlierReportOnlyWhenTheNewOneIsComplete) {
  ScratchFolder scratch;
  const fs::path target = scratch.path() / "report";
  writeReport(target, "first");
  ASSERT_TRUE(isPenumbraReport(target));
  {
    ReportFolder folder(fs::path(target.string() + "/"), false);
    folder.createStaging();
    writeFile(folder.staging() / "index.html", "second");
    EXPECT_EQ(readFile(target / "index.html"), "first");  // untouched while staging
    folder.commit();
  }
  EXPECT_EQ(readFile(target / "index.html"), "second");
  EXPECT_TRUE(isPenumbraReport(target));
  EXPECT_EQ(entriesStartingWith(scratch.path(), "report.").size(), 0u);
}

TEST(ReportFolder, KeepsAnEarlierReportHoldingFilesPenumbraDidNotWrite) {
  // A user's notes saved inside an old report (even in one of its subfolders) are not the
  // report's: replacing it needs --force, and the error names the file.
  ScratchFolder scratch;
  const fs::path target = scratch.path() / "report";
  {
    ReportFolder folder(target, false);
    folder.createStaging();
    fs::create_directories(folder.staging() / "images");
    writeFile(folder.staging() / "images" / "vsm.png", "image");
    writeFile(folder.staging() / "index.html", "first");
    folder.commit();
  }
  writeFile(target / "images" / "my-notes.txt", "mine");
  const std::string error = errorOf([&] {
    ReportFolder folder(target, false);
    folder.createStaging();
    folder.commit();
  });
  EXPECT_NE(error.find("images/my-notes.txt"), std::string::npos) << error;
  EXPECT_EQ(readFile(target / "images" / "my-notes.txt"), "mine");
  EXPECT_EQ(readFile(target / "index.html"), "first");
}

TEST(ReportFolder, ReplacesAnEmptyFolder) {
  ScratchFolder scratch;
  fs::create_directory(scratch.path() / "report");
  writeReport(scratch.path() / "report", "new");
  EXPECT_EQ(readFile(scratch.path() / "report" / "index.html"), "new");
}

TEST(ReportFolder, ForceReplacesAFolderThatIsNotAReport) {
  ScratchFolder scratch;
  writeFile(scratch.path() / "old" / "data.txt", "old");
  ReportFolder folder(scratch.path() / "old", true);
  folder.createStaging();
  writeFile(folder.staging() / "index.html", "new");
  folder.commit();
  EXPECT_FALSE(fs::exists(scratch.path() / "old" / "data.txt"));
  EXPECT_EQ(readFile(scratch.path() / "old" / "index.html"), "new");
}

TEST(ReportFolder, AnUncommittedStagingFolderIsRemovedAndTheTargetKept) {
  ScratchFolder scratch;
  const fs::path target = scratch.path() / "report";
  writeReport(target, "kept");
  const auto before = snapshot(target);
  {
    ReportFolder folder(target, false);
    folder.createStaging();
    ASSERT_TRUE(fs::exists(folder.staging()));
    writeFile(folder.staging() / "images" / "half.png", "half");
  }  // e.g. an exception during the run
  EXPECT_EQ(snapshot(target), before);
  EXPECT_EQ(entriesStartingWith(scratch.path(), "report.").size(), 0u);
}

TEST(ReportFolder, AFolderThatAppearsDuringTheRunIsNotReplaced) {
  ScratchFolder scratch;
  const fs::path target = scratch.path() / "report";
  ReportFolder folder(target, false);
  folder.createStaging();
  writeFile(folder.staging() / "index.html", "new");
  writeFile(target / "mine.txt", "mine");
  const std::string message = errorOf([&] { folder.commit(); });
  EXPECT_NE(message.find("appeared during the run"), std::string::npos) << message;
  EXPECT_EQ(readFile(target / "mine.txt"), "mine");
  // The finished report is kept for the user, at the path the message names.
  const std::vector<std::string> staged = entriesStartingWith(scratch.path(), "report.partial-");
  ASSERT_EQ(staged.size(), 1u);
  EXPECT_NE(message.find(staged[0]), std::string::npos);
  EXPECT_EQ(readFile(scratch.path() / staged[0] / "index.html"), "new");
}

TEST(ReportFolder, CannotCreateBelowAFile) {
  // "Cannot create" without permission bits, which root ignores.
  ScratchFolder scratch;
  writeFile(scratch.path() / "file", "text");
  ReportFolder folder(scratch.path() / "file" / "report", false);
  const std::string message = errorOf([&] { folder.createStaging(); });
  EXPECT_NE(message.find("cannot write the output next to"), std::string::npos) << message;
  EXPECT_NE(message.find("Not a directory"), std::string::npos) << message;
  EXPECT_EQ(readFile(scratch.path() / "file"), "text");
}

TEST(ReportFolder, ReadOnlyParentIsRefusedWithTheReason) {
  ScratchFolder scratch;
  // The scratch folder itself must be traversable by the unprivileged child below.
  fs::permissions(scratch.path(), fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
  const fs::path parent = scratch.path() / "locked";
  fs::create_directory(parent);
  fs::permissions(parent, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read |
                              fs::perms::others_exec);
  // Root writes into a read-only folder anyway, so as root the attempt runs in a child that has
  // given up root for the unprivileged user 65534 (nobody), to whom the folder is read-only too.
  int channel[2];
  ASSERT_EQ(pipe(channel), 0);
  const pid_t child = fork();
  if (child == 0) {
    close(channel[0]);
    if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) _exit(2);
    std::string message;
    try {
      ReportFolder folder(parent / "report", false);
      message = errorOf([&] { folder.createStaging(); });
    } catch (const std::exception& e) {
      message = std::string("unexpected: ") + e.what();
    }
    const ssize_t written = write(channel[1], message.data(), message.size());
    _exit(written == ssize_t(message.size()) ? 0 : 3);
  }
  close(channel[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = read(channel[0], buffer, sizeof buffer)) > 0;)
    message.append(buffer, size_t(n));
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  fs::permissions(parent, fs::perms::owner_all);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "child status " << status;
  EXPECT_NE(message.find("cannot write the output next to"), std::string::npos) << message;
  EXPECT_NE(message.find("Permission denied"), std::string::npos) << message;
}

TEST(ReportFolder, RemovesLeftoversOfDeadRunsThatCarryTheMarkerOnly) {
  ScratchFolder scratch;
  const long dead = deadPid();
  const long alive = long(getppid());
  const std::string marker = std::string(kReportMarkerFile);
  const fs::path deadStaging = scratch.path() / ("report.partial-" + std::to_string(dead));
  writeFile(deadStaging / marker, "penumbra report 1\nstaging " + std::to_string(dead) + "\n");
  const fs::path deadAside = scratch.path() / ("report.replaced-" + std::to_string(dead));
  writeFile(deadAside / marker, "penumbra report 1\n");
  // Not penumbra's (no marker, or a marker naming another process), or a live run's: kept.
  const fs::path unmarked = scratch.path() / ("report.partial-" + std::to_string(dead + 1000000));
  writeFile(unmarked / "thesis.tex", "mine");
  const fs::path otherPid = scratch.path() / ("report.replaced-" + std::to_string(dead + 2000000));
  writeFile(otherPid / "notes.txt", "mine");
  const fs::path live = scratch.path() / ("report.partial-" + std::to_string(alive));
  writeFile(live / marker, "penumbra report 1\nstaging " + std::to_string(alive) + "\n");
  const fs::path otherTarget = scratch.path() / ("other.partial-" + std::to_string(dead));
  writeFile(otherTarget / marker, "penumbra report 1\nstaging " + std::to_string(dead) + "\n");

  ReportFolder folder(scratch.path() / "report", false);
  folder.createStaging();
  EXPECT_FALSE(fs::exists(deadStaging));
  EXPECT_FALSE(fs::exists(deadAside));
  EXPECT_EQ(readFile(unmarked / "thesis.tex"), "mine");
  EXPECT_EQ(readFile(otherPid / "notes.txt"), "mine");
  EXPECT_TRUE(fs::exists(live / marker));
  EXPECT_TRUE(fs::exists(otherTarget / marker));  // another target's leftovers are its own business
}

// A killed run's staging folder loses exactly what its marker lists: a file someone put into it,
// and the folders that hold such files, stay. The same for a set-aside earlier report.
TEST(ReportFolder, RemovesOnlyTheEntriesADeadRunListed) {
  ScratchFolder scratch;
  const long dead = deadPid();
  const std::string marker = std::string(kReportMarkerFile);
  const fs::path staging = scratch.path() / ("report.partial-" + std::to_string(dead));
  writeFile(staging / marker, "penumbra report 1\nstaging " + std::to_string(dead) +
                                  "\nentry images\nentry images/vsm.png\nentry plots\n"
                                  "entry plots/grid.png\nentry index.html\nentry ../outside.txt\n");
  writeFile(staging / "images" / "vsm.png", "penumbra's");
  writeFile(staging / "plots" / "grid.png", "penumbra's");
  writeFile(staging / "plots" / "mine.dat", "a user's");
  writeFile(staging / "notes.txt", "a user's");
  writeFile(scratch.path() / "outside.txt", "a user's");
  const fs::path aside = scratch.path() / ("report.replaced-" + std::to_string(dead));
  writeFile(aside / marker, "penumbra report 1\nentry index.html\n");
  writeFile(aside / "index.html", "penumbra's");

  ReportFolder folder(scratch.path() / "report", false);
  folder.createStaging();
  EXPECT_FALSE(fs::exists(staging / "images"));
  EXPECT_FALSE(fs::exists(staging / "plots" / "grid.png"));
  EXPECT_FALSE(fs::exists(staging / "index.html"));
  EXPECT_EQ(readFile(staging / "plots" / "mine.dat"), "a user's");
  EXPECT_EQ(readFile(staging / "notes.txt"), "a user's");
  EXPECT_EQ(readFile(scratch.path() / "outside.txt"), "a user's");
  EXPECT_FALSE(fs::exists(aside));  // everything in it was listed: gone, marker and folder too
}

// A listed entry reached through a symbolic link would be removed outside the folder: a link in a
// dead run's folder and one in an earlier report are never followed, and a report holding a link
// is not penumbra's (it writes none). A marker naming another process keeps its folder.
TEST(ReportFolder, NeverRemovesThroughALinkNorAnotherProcesssFolder) {
  ScratchFolder scratch;
  const long dead = deadPid();
  const std::string marker = std::string(kReportMarkerFile);
  writeFile(scratch.path() / "victim" / "secret.txt", "a user's");
  const fs::path staging = scratch.path() / ("report.partial-" + std::to_string(dead));
  writeFile(staging / marker, "penumbra report 1\nstaging " + std::to_string(dead) +
                                  "\nentry link\nentry link/secret.txt\n");
  fs::create_directory_symlink(scratch.path() / "victim", staging / "link");
  const fs::path other = scratch.path() / ("report.partial-" + std::to_string(dead + 1000000));
  writeFile(other / marker, "penumbra report 1\nstaging " + std::to_string(dead) +
                                "\nentry index.html\n");
  writeFile(other / "index.html", "another run's");
  {
    ReportFolder folder(scratch.path() / "report", false);
    folder.createStaging();
  }
  EXPECT_EQ(readFile(scratch.path() / "victim" / "secret.txt"), "a user's");
  EXPECT_FALSE(fs::exists(fs::symlink_status(staging / "link")));  // the link itself was listed
  EXPECT_EQ(readFile(other / "index.html"), "another run's");

  const fs::path earlier = scratch.path() / "earlier";
  writeFile(earlier / marker, "penumbra report 1\nentry link\nentry link/secret.txt\n");
  fs::create_directory_symlink(scratch.path() / "victim", earlier / "link");
  EXPECT_NE(errorOf([&] { ReportFolder(earlier, false); }).find("did not write there (link)"),
            std::string::npos);
  EXPECT_EQ(readFile(scratch.path() / "victim" / "secret.txt"), "a user's");
}

// A marker that is a FIFO or a device is not read (it would block or never end).
TEST(ReportFolder, AMarkerThatIsNotARegularFileIsNotPenumbras) {
  ScratchFolder scratch;
  fs::create_directories(scratch.path() / "out");
  ASSERT_EQ(mkfifo((scratch.path() / "out" / std::string(kReportMarkerFile)).c_str(), 0600), 0);
  EXPECT_NE(errorOf([&] { ReportFolder(scratch.path() / "out", false); })
                .find("is not a penumbra report"),
            std::string::npos);
  fs::create_directories(scratch.path() / "dev");
  fs::create_symlink("/dev/zero", scratch.path() / "dev" / std::string(kReportMarkerFile));
  EXPECT_NE(errorOf([&] { ReportFolder(scratch.path() / "dev", false); })
                .find("is not a penumbra report"),
            std::string::npos);
}

// The staging folder is private while it is written.
TEST(ReportFolder, StagingIsPrivateUntilCommitted) {
  ScratchFolder scratch;
  ReportFolder folder(scratch.path() / "report", false);
  folder.createStaging();
  EXPECT_EQ(fs::status(folder.staging()).permissions() & fs::perms::all, fs::perms::owner_all);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  folder.commit();
  EXPECT_EQ(fs::status(scratch.path() / "report").permissions() & fs::perms::all,
            fs::perms(0777 & ~mask));
}

// What this run writes is listed before it is written, so a SIGKILL at any point leaves a list
// of exactly this run's files.
TEST(ReportFolder, StagingMarkerListsEachFileAsItIsWritten) {
  ScratchFolder scratch;
  ReportFolder folder(scratch.path() / "report", false);
  folder.createStaging();
  writeTextFile(folder.staging() / "index.html", "page");
  createOutputDirectory(folder.staging() / "images");
  writeTextFile(folder.staging() / "images" / "a.txt", "a");
  writeTextFile(scratch.path() / "elsewhere.txt", "not in the staging folder");
  EXPECT_EQ(readFile(folder.staging() / kReportMarkerFile),
            "penumbra report 1\nstaging " + std::to_string(getpid()) +
                "\nentry index.html\nentry images\nentry images/a.txt\n");
  folder.discard();
  // After the folder is done with, nothing is listed any more.
  writeTextFile(scratch.path() / "after.txt", "x");
  EXPECT_TRUE(fs::exists(scratch.path() / "after.txt"));
}

}  // namespace
}  // namespace penumbra::compare
