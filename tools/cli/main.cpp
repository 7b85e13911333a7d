// The `penumbra` command line: subcommands register themselves; errors become a message and a
// non-zero exit.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "accuracy_command.h"
#include "bench_command.h"
#include "compare_command.h"
#include "curves_command.h"
#include "figures_command.h"
#include "penumbra/error.h"
#include "render_command.h"
#include "tune_command.h"

int main(int argc, char** argv) {
  CLI::App app{"penumbra: filtered shadow maps, measured against an exact reference"};
  app.require_subcommand(1);
  penumbra::cli::registerAccuracyCommand(app);
  penumbra::cli::registerBenchCommand(app);
  penumbra::cli::registerCompareCommand(app);
  penumbra::cli::registerCurvesCommand(app);
  penumbra::cli::registerFiguresCommand(app);
  penumbra::cli::registerRenderCommand(app);
  penumbra::cli::registerTuneCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "penumbra: error: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const penumbra::Error& e) {
    std::cerr << "penumbra: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    // Library failures that are not penumbra::Error (std::filesystem, allocation): still one
    // line and a non-zero exit, never an abort.
    std::cerr << "penumbra: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
