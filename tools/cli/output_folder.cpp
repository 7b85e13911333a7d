// The subcommands' output folder: compare::ReportFolder behind their common options.
#include "output_folder.h"

namespace penumbra::cli {

void addOutputOptions(CLI::App& command, OutputOptions& options, const std::string& contents) {
  command
      .add_option("-o,--out", options.outDir,
                  "output folder for " + contents +
                      "; an earlier penumbra output there is replaced once the new one is "
                      "complete, any other non-empty folder is refused")
      ->capture_default_str();
  command.add_flag(
      "--force", options.force,
      "replace --out even when it is not a penumbra output (deletes everything in it)");
}

CommandOutput::CommandOutput(const OutputOptions& options)
    : folder_(options.outDir, options.force) {}

const std::filesystem::path& CommandOutput::begin(InterruptCleanup& interrupt) {
  interrupt.uninterrupted([&] {
    folder_.createStaging();
    interrupt.setCleanup([staging = folder_.staging()] { compare::removeReportStaging(staging); });
  });
  return folder_.staging();
}

void CommandOutput::finish(InterruptCleanup& interrupt) {
  interrupt.uninterrupted([&] {
    folder_.commit();
    interrupt.setCleanup({});
  });
}

}  // namespace penumbra::cli
