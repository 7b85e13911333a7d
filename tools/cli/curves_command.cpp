// `penumbra curves`: parses options, calls penumbra::computeCurves, writes CSV and plot.
#include "curves_command.h"

#include <filesystem>
#include <iostream>
#include <memory>

#include "interrupt_cleanup.h"
#include "output_folder.h"
#include "penumbra/curves.h"
#include "technique_options.h"

namespace penumbra::cli {
namespace {

struct CurvesOptions {
  std::string occluders = "0.3:0.5,0.5:0.5";
  OutputOptions output{"out/curves"};
  int samples = 1001;
  bool noPlot = false;
  TechniqueOptions technique;
};

void runCurves(const CurvesOptions& options) {
  if (printTechniqueListIfAsked(options.technique)) return;
  CurvesRequest request;
  request.occluders = parseDepthDistribution(options.occluders);
  request.techniques = selectedTechniques(options.technique);
  request.params = selectedParams(options.technique, request.techniques);
  request.samples = options.samples;
  CommandOutput output(options.output);
  const CurvesTable table = computeCurves(request);

  namespace fs = std::filesystem;
  InterruptCleanup interrupt;
  const fs::path dir = output.begin(interrupt);
  writeCurvesCsv(table, dir / "curves.csv");
  if (!options.noPlot) {
    plotCurves(dir / "curves.csv", table,
               "shadow test over receiver depth, occluders " + options.occluders,
               dir / "curves.png");
  }
  output.finish(interrupt);
  std::cout << "wrote " << (output.target() / "curves.csv").string() << "\n";
  if (!options.noPlot) std::cout << "wrote " << (output.target() / "curves.png").string() << "\n";
}

}  // namespace

void registerCurvesCommand(CLI::App& app) {
  auto options = std::make_shared<CurvesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "curves",
      "Plot every technique's shadow test against receiver depth for a depth distribution "
      "inside one filter region (ESM Fig. 2, CSM Fig. 3, thesis Fig. 3.4).");
  cmd->add_option("--occluders", options->occluders,
                  "DEPTH:WEIGHT,... occluder depths in [0,1] with their share of the filter "
                  "region; the planar receiver fills the rest")
      ->capture_default_str();
  addOutputOptions(*cmd, options->output, "curves.csv and curves.png");
  cmd->add_option("--samples", options->samples, "receiver depths evenly over [0,1], 2..100000")
      ->capture_default_str();
  cmd->add_flag("--no-plot", options->noPlot, "write the CSV only");
  addTechniqueOptions(*cmd, options->technique);
  cmd->callback([options] { runCurves(*options); });
}

}  // namespace penumbra::cli
