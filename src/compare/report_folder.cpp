// The report's target folder, its staging folder and the swap between them.
#include "penumbra/compare/report_folder.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/output_journal.h"

namespace penumbra::compare {
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kMarkerLine = "penumbra report 1";
constexpr std::string_view kStagingSuffix = ".partial-";
constexpr std::string_view kReplacedSuffix = ".replaced-";

enum class Existing { None, EmptyFolder, Report, Other };

std::string quoted(const fs::path& path) {
  return "'" + path.string() + "'";
}

// A marker lists a report's entries: far below this in any real report.
constexpr std::uintmax_t kMaxMarkerBytes = 16u << 20;

// The marker's lines, or nothing when `folder` has no marker that is a regular file of a sane
// size (a FIFO or a link to a device planted there must not block or flood the read).
std::vector<std::string> markerLines(const fs::path& folder) {
  const fs::path marker = folder / kReportMarkerFile;
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(marker, ec);
  if (ec || !fs::is_regular_file(status)) return {};
  const std::uintmax_t bytes = fs::file_size(marker, ec);
  if (ec || bytes > kMaxMarkerBytes) return {};
  std::ifstream in(marker);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void writeMarker(const fs::path& folder, const std::string& text) {
  std::ofstream out(folder / kReportMarkerFile, std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw Error("cannot write the report marker in " + quoted(folder));
}

// Every entry below `folder` (relative, generic separators) but the marker itself, sorted.
std::vector<std::string> entriesBelow(const fs::path& folder) {
  std::vector<std::string> entries;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const std::string relative = it->path().lexically_relative(folder).generic_string();
    if (relative != kReportMarkerFile) entries.push_back(relative);
  }
  if (ec) throw Error("cannot list the output folder " + quoted(folder) + ": " + ec.message());
  std::sort(entries.begin(), entries.end());
  return entries;
}

// A finished report's marker lists everything the writer put there, so that a later run
// replaces the folder only while it holds nothing else.
std::string finishedMarker(const fs::path& folder) {
  std::string text = std::string(kMarkerLine) + "\n";
  for (const std::string& entry : entriesBelow(folder)) text += "entry " + entry + "\n";
  return text;
}

// The first entry of a report folder that its marker does not list, or "".
std::string unlistedEntry(const fs::path& folder) {
  const std::vector<std::string> lines = markerLines(folder);
  std::vector<std::string> listed;
  for (const std::string& line : lines) {
    if (line.rfind("entry ", 0) == 0) listed.push_back(line.substr(6));
  }
  std::sort(listed.begin(), listed.end());
  for (const std::string& entry : entriesBelow(folder)) {
    if (!std::binary_search(listed.begin(), listed.end(), entry)) return entry;
  }
  return "";
}

// The first symbolic link below `folder` (relative), or "": penumbra writes none.
std::string firstLinkBelow(const fs::path& folder) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_symlink(ec)) return it->path().lexically_relative(folder).generic_string();
  }
  return "";
}

std::string stagingMarker(long pid) {
  return std::string(kMarkerLine) + "\nstaging " + std::to_string(pid) + "\n";
}

Existing classify(const fs::path& target) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(target, ec);
  if (status.type() == fs::file_type::not_found) return Existing::None;
  if (ec) throw Error("cannot inspect the output folder " + quoted(target) + ": " + ec.message());
  if (fs::is_symlink(status)) {
    throw Error("the output folder " + quoted(target) +
                " is a symbolic link; give the folder it points to");
  }
  if (!fs::is_directory(status)) {
    throw Error("the output folder " + quoted(target) + " exists and is not a folder");
  }
  if (isPenumbraReport(target)) {
    return unlistedEntry(target).empty() && firstLinkBelow(target).empty() ? Existing::Report
                                                                          : Existing::Other;
  }
  const bool empty = fs::is_empty(target, ec);
  if (ec) throw Error("cannot inspect the output folder " + quoted(target) + ": " + ec.message());
  return empty ? Existing::EmptyFolder : Existing::Other;
}

void refuseOther(const fs::path& target) {
  if (isPenumbraReport(target)) {
    throw Error("the output folder " + quoted(target) +
                " holds files penumbra did not write there (" +
                (unlistedEntry(target).empty() ? firstLinkBelow(target) : unlistedEntry(target)) +
                "); move them out, choose another folder, or pass --force to replace it and "
                "everything in it");
  }
  throw Error("the output folder " + quoted(target) +
              " exists and is not a penumbra report (it has no " + std::string(kReportMarkerFile) +
              " file); choose another folder, or pass --force to replace it and everything in it");
}

// `target` made absolute and lexically normal, without a trailing separator.
fs::path normalisedTarget(const fs::path& outDir) {
  if (outDir.empty()) throw Error("the output folder path is empty; name a folder to write to");
  std::error_code ec;
  fs::path target = fs::absolute(outDir, ec).lexically_normal();
  if (ec) throw Error("cannot resolve the output folder " + quoted(outDir) + ": " + ec.message());
  if (!target.has_filename() && target.has_relative_path()) target = target.parent_path();
  if (!target.has_relative_path()) {
    throw Error("the output folder " + quoted(outDir) + " is the file-system root");
  }
  const fs::path cwd = fs::current_path(ec);
  if (!ec) {
    // Compare real locations, so that "..", symbolic links in the prefix and "." all count.
    std::error_code realError, hereError;
    const fs::path real = fs::weakly_canonical(target, realError);
    const fs::path here = fs::weakly_canonical(cwd, hereError);
    const fs::path inside = here.lexically_relative(real);
    if (!realError && !hereError && !inside.empty() && *inside.begin() != "..") {
      throw Error("the output folder " + quoted(outDir) +
                  " is the current folder or contains it; name a folder below it");
    }
  }
  return target;
}

bool processIsGone(long pid) {
  return pid > 0 && ::kill(pid_t(pid), 0) == -1 && errno == ESRCH;
}

// The pid in "<name><suffix><pid>", or 0.
long pidAfter(std::string_view entry, std::string_view prefix) {
  if (entry.substr(0, prefix.size()) != prefix) return 0;
  const std::string_view digits = entry.substr(prefix.size());
  long pid = 0;
  auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) return 0;
  return pid;
}

// True when the path from `folder` to the entry `relative` passes through a symbolic link: the
// entry would then be resolved outside the folder. (The entry itself may be a link: removing it
// removes the link.) penumbra never writes links, so such an entry is not its own.
bool passesThroughLink(const fs::path& folder, const fs::path& relative) {
  fs::path at = folder;
  for (auto part = relative.begin(); part != relative.end(); ++part) {
    if (std::next(part) == relative.end()) return false;
    at /= *part;
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(at, ec))) return true;
  }
  return false;
}

// Removes from `folder` the entries its marker lists ("entry <relative path>"), deepest first,
// folders only once empty, then the marker and the folder itself if nothing else is left: what
// someone else put there stays, and nothing is reached through a link.
void removeListedEntries(const fs::path& folder, const std::vector<std::string>& markerText) {
  std::vector<std::string> listed;
  for (const std::string& line : markerText) {
    if (line.rfind("entry ", 0) != 0) continue;
    const fs::path relative = fs::path(line.substr(6)).lexically_normal();
    if (relative.empty() || relative.is_absolute() || *relative.begin() == ".." ||
        relative == kReportMarkerFile) {
      continue;
    }
    listed.push_back(relative.generic_string());
  }
  // Reverse order puts "a/b" before "a": children go before their folder.
  std::sort(listed.rbegin(), listed.rend());
  std::error_code ec;
  for (const std::string& entry : listed) {
    if (passesThroughLink(folder, entry)) continue;
    const fs::path path = folder / entry;
    if (fs::is_directory(fs::symlink_status(path, ec))) {
      if (!fs::is_empty(path, ec)) continue;
    }
    fs::remove(path, ec);
  }
  if (entriesBelow(folder).empty()) {
    fs::remove(folder / kReportMarkerFile, ec);
    fs::remove(folder, ec);
  }
}

// Staging and set-aside folders of runs to the same target whose process is gone (a run killed
// by SIGKILL cannot clean up after itself). Only folders carrying penumbra's marker are touched,
// a staging folder's marker must also name the dead process, and only the entries the marker
// lists are removed: a staging folder's marker lists each file before it is written
// (output_journal.h), a set-aside report's every entry of the finished report.
void removeStaleFolders(const fs::path& target) {
  const std::string name = target.filename().string();
  const std::string stagingPrefix = name + std::string(kStagingSuffix);
  const std::string replacedPrefix = name + std::string(kReplacedSuffix);
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(target.parent_path(), ec)) {
    const std::string entryName = entry.path().filename().string();
    const long stagingPid = pidAfter(entryName, stagingPrefix);
    const long replacedPid = pidAfter(entryName, replacedPrefix);
    const long pid = stagingPid != 0 ? stagingPid : replacedPid;
    if (pid == 0 || pid == long(::getpid()) || !processIsGone(pid)) continue;
    std::error_code typeError;
    if (!entry.is_directory(typeError) || entry.is_symlink(typeError)) continue;
    // Only this user's leftovers: in a shared folder (/tmp) another user's are not ours to clean.
    struct stat owner {};
    if (::lstat(entry.path().c_str(), &owner) != 0 || owner.st_uid != ::geteuid()) continue;
    const std::vector<std::string> lines = markerLines(entry.path());
    if (lines.empty() || lines[0] != kMarkerLine) continue;
    if (stagingPid != 0 && (lines.size() < 2 || lines[1] != "staging " + std::to_string(pid))) {
      continue;
    }
    try {
      removeListedEntries(entry.path(), lines);
    } catch (const Error&) {
      // An unreadable leftover stays; it is not this run's to force.
    }
  }
}

}  // namespace

bool isPenumbraReport(const fs::path& folder) {
  const std::vector<std::string> lines = markerLines(folder);
  return !lines.empty() && lines[0] == kMarkerLine;
}

void removeReportStaging(const fs::path& staging) noexcept {
  // A writer may still be creating files in it: retry until it is gone.
  for (int attempt = 0; attempt < 20; ++attempt) {
    std::error_code ec;
    fs::remove_all(staging, ec);
    if (!fs::exists(fs::symlink_status(staging, ec))) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

ReportFolder::ReportFolder(const fs::path& outDir, bool force)
    : target_(normalisedTarget(outDir)), force_(force) {
  if (classify(target_) == Existing::Other && !force_) refuseOther(target_);
}

ReportFolder::~ReportFolder() {
  discard();
}

void ReportFolder::createStaging() {
  const fs::path parent = target_.parent_path();
  const long pid = long(::getpid());
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) {
    throw Error("cannot write the output next to " + quoted(target_) + ": cannot create " +
                quoted(parent) + ": " + ec.message());
  }
  removeStaleFolders(target_);
  const fs::path staging =
      parent / (target_.filename().string() + std::string(kStagingSuffix) + std::to_string(pid));
  if (fs::exists(fs::symlink_status(staging, ec))) {
    // This process's own earlier staging folder (an earlier ReportFolder that was not discarded).
    const std::vector<std::string> lines = markerLines(staging);
    if (lines.size() < 2 || lines[1] != "staging " + std::to_string(pid)) {
      throw Error("cannot write the output next to " + quoted(target_) + ": " + quoted(staging) +
                  " exists and is not this run's staging folder");
    }
    fs::remove_all(staging, ec);
  }
  if (!fs::create_directory(staging, ec) || ec) {
    throw Error("cannot write the output next to " + quoted(target_) + ": cannot create " +
                quoted(staging) + (ec ? ": " + ec.message() : std::string()));
  }
  staging_ = staging;
  try {
    // Private while it is written: no one else can plant a link for a writer to follow.
    fs::permissions(staging_, fs::perms::owner_all, ec);
    if (ec) throw Error("cannot make " + quoted(staging_) + " private: " + ec.message());
    writeMarker(staging_, stagingMarker(pid));
    startOutputJournal(staging_, staging_ / kReportMarkerFile);
  } catch (const Error& e) {
    discard();
    throw Error("cannot write the output next to " + quoted(target_) + ": " + e.what());
  }
}

void ReportFolder::commit() {
  if (staging_.empty()) throw Error("no staged output to move to " + quoted(target_));
  stopOutputJournal();
  {
    // The finished output gets the permissions the user's umask gives a new folder.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    std::error_code ec;
    fs::permissions(staging_, fs::perms(0777 & ~mask), ec);
  }
  writeMarker(staging_, finishedMarker(staging_));
  // The run took a while: check the target again.
  const Existing existing = classify(target_);
  if (existing == Existing::Other && !force_) {
    const fs::path kept = staging_;
    staging_.clear();  // the finished report stays where it is
    throw Error("the output folder " + quoted(target_) +
                " appeared during the run and is not a penumbra report; the new report is in " +
                quoted(kept));
  }
  std::error_code ec;
  if (existing == Existing::None) {
    fs::rename(staging_, target_, ec);
    if (ec) {
      throw Error("cannot move the finished output to " + quoted(target_) + ": " + ec.message());
    }
    staging_.clear();
    return;
  }
  const fs::path aside =
      target_.parent_path() / (target_.filename().string() + std::string(kReplacedSuffix) +
                               std::to_string(long(::getpid())));
  fs::rename(target_, aside, ec);
  if (ec) {
    throw Error("cannot move the earlier output " + quoted(target_) + " aside: " + ec.message());
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    std::error_code restore;
    fs::rename(aside, target_, restore);
    throw Error("cannot move the finished output to " + quoted(target_) + ": " + ec.message());
  }
  staging_.clear();
  // An empty folder goes with rmdir, which cannot delete anything that appeared in it meanwhile.
  // An earlier report loses only what its marker lists (a file that appeared in it meanwhile
  // keeps the folder); --force replaces a foreign folder whole, as it says.
  if (existing == Existing::EmptyFolder) {
    fs::remove(aside, ec);
  } else if (existing == Existing::Report) {
    removeListedEntries(aside, markerLines(aside));
    const bool kept = fs::exists(fs::symlink_status(aside, ec));
    ec.clear();  // "no such file" is the success here
    if (kept) {
      throw Error("the report is in " + quoted(target_) + "; files that appeared in the earlier "
                  "one during the run were kept in " + quoted(aside));
    }
  } else {
    fs::remove_all(aside, ec);
  }
  if (ec) {
    throw Error("the report is in " + quoted(target_) +
                ", but the earlier one could not be removed from " + quoted(aside) + ": " +
                ec.message());
  }
}

void ReportFolder::discard() noexcept {
  if (staging_.empty()) return;
  stopOutputJournal();
  removeReportStaging(staging_);
  staging_.clear();
}

}  // namespace penumbra::compare
