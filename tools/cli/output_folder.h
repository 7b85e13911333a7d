// The folder every subcommand writes (`--out`), by one rule (compare::ReportFolder): checked
// before any work, written as a staging folder beside it, swapped in only when complete. An
// existing folder is replaced only when it is empty or a penumbra output holding nothing
// penumbra did not write, unless --force; the file-system root, the current folder and folders
// containing it are always refused. SIGINT and SIGTERM remove the staging folder.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "interrupt_cleanup.h"
#include "penumbra/compare/report_folder.h"

namespace penumbra::cli {

struct OutputOptions {
  std::string outDir;
  bool force = false;
};

// Adds -o,--out (default `options.outDir`) and --force; `contents` says what the folder holds.
void addOutputOptions(CLI::App& command, OutputOptions& options, const std::string& contents);

class CommandOutput {
 public:
  // Checks --out without touching the file system; throws Error.
  explicit CommandOutput(const OutputOptions& options);

  // Creates the staging folder, which a signal from now on removes; returns it.
  const std::filesystem::path& begin(InterruptCleanup& interrupt);
  // Swaps the finished staging folder in as the target.
  void finish(InterruptCleanup& interrupt);

  const std::filesystem::path& target() const { return folder_.target(); }

 private:
  compare::ReportFolder folder_;
};

}  // namespace penumbra::cli
