// The list of what a run wrote, kept as it writes. While a staging folder is being filled, every
// file and folder penumbra creates in it is first appended to the folder's marker ("entry
// <relative path>"), so that a run killed by SIGKILL leaves behind exactly the list of what it
// wrote: the next run removes those entries and nothing else (compare/report_folder.h).
#pragma once

#include <filesystem>

namespace penumbra {

// Starts listing the paths below `folder` in `journal` (appended to, never truncated).
void startOutputJournal(const std::filesystem::path& folder, const std::filesystem::path& journal);
// Stops listing; paths recorded later are ignored.
void stopOutputJournal() noexcept;

// Lists `path` (and the folders between it and the journalled folder) before it is created.
// Paths outside the journalled folder, or with no journal started, are ignored. Throws Error
// when the journal cannot be written: a file that could not be listed is not created.
void recordOutput(const std::filesystem::path& path);

// Records, then creates the folder `path` and its missing parents; throws Error, also when the
// journalled folder no longer exists (an interrupt removed it: it must not come back).
void createOutputDirectory(const std::filesystem::path& path);

}  // namespace penumbra
