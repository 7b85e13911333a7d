// Where a comparison report goes, and how it replaces an earlier one without ever deleting
// anything penumbra did not write. A report is written into a staging folder beside its target
// (`<target>.partial-<pid>`) and swapped in only when complete. A folder counts as a penumbra
// report when it holds the marker file kReportMarkerFile; only such a folder, an empty folder,
// or (with `force`) any folder is replaced. Staging folders left by a killed run are removed by
// the next run to the same target once their process is gone.
#pragma once

#include <filesystem>
#include <string_view>

namespace penumbra::compare {

// Written into every report (and staging) folder; its first line is "penumbra report <version>".
inline constexpr std::string_view kReportMarkerFile = ".penumbra-report";

// True when `folder` holds a marker whose first line names a penumbra report.
bool isPenumbraReport(const std::filesystem::path& folder);

// Removes a staging folder, tolerating a writer that is still adding files to it; never throws.
// Meant for interrupt handling, where the ReportFolder itself may be in use.
void removeReportStaging(const std::filesystem::path& staging) noexcept;

class ReportFolder {
 public:
  // Checks the target without touching the file system: the path must be non-empty, must not be
  // the file-system root, the current folder or a folder containing it, a symbolic link or a
  // file; an existing folder must be empty or a penumbra report unless `force`. Throws Error.
  ReportFolder(const std::filesystem::path& outDir, bool force);
  ~ReportFolder();  // discards an uncommitted staging folder
  ReportFolder(const ReportFolder&) = delete;
  ReportFolder& operator=(const ReportFolder&) = delete;

  // Creates the parent folders and the staging folder beside the target (with a marker naming
  // this process) after removing the staging folders of dead earlier runs to the same target.
  // Throws Error when the location is not writable.
  void createStaging();

  // Swaps the complete staging folder in: an existing target (checked again) moves aside, the
  // staging folder takes its name, then the old one is removed. Throws Error; when the swap
  // fails the old target is put back.
  void commit();

  // Removes the staging folder if there is one; never throws.
  void discard() noexcept;

  const std::filesystem::path& target() const { return target_; }    // absolute, normalised
  const std::filesystem::path& staging() const { return staging_; }  // empty when none

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool force_ = false;
};

}  // namespace penumbra::compare
