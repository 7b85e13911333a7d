// `penumbra figures`: options in, penumbra::compare::writePaperFigures out.
#include "figures_command.h"

#include <chrono>
#include <iostream>
#include <memory>

#include "command_line.h"
#include "interrupt_cleanup.h"
#include "output_folder.h"
#include "penumbra/compare/paper_figures.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/renderer.h"

namespace penumbra::cli {
namespace {

struct FiguresCommandOptions {
  compare::FiguresOptions figures;
  OutputOptions output{"out/figures"};
};

void runFigures(FiguresCommandOptions& o) {
  CommandOutput output(o.output);
  InterruptCleanup interrupt;  // before the GL context: its driver threads inherit the mask
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  const auto start = std::chrono::steady_clock::now();
  const std::filesystem::path dir = output.begin(interrupt);
  compare::writePaperFigures(renderer, o.figures, dir, [&](const std::string& step) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[" << int(s) << " s] " << step << "\n" << std::flush;
  });
  output.finish(interrupt);
  std::cout << "wrote " << (output.target() / "index.html").string() << "\n";
}

}  // namespace

void registerFiguresCommand(CLI::App& app) {
  auto o = std::make_shared<FiguresCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "figures", "The seed papers' figures and tables regenerated with penumbra, on one page.");
  compare::FiguresOptions& f = o->figures;
  cmd->add_option("--shadow-size", f.shadowMapSize, "shadow-map size of the rendered figures")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd->add_option("--width", f.width, "frame width of the rendered figures")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd->add_option("--height", f.height, "frame height of the rendered figures")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd->add_option("--bench-shadow-size", f.benchSizes.shadowMapSize,
                  "shadow-map size of the bench tables (the papers': 2048)")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd->add_option("--bench-repeat", f.benchRepeats, "timed frames per bench case (medians)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  addOutputOptions(*cmd, o->output, "the figures page");
  cmd->callback([o, cmd] {
    compare::FiguresOptions& fo = o->figures;
    fo.benchSizes.width = fo.width;
    fo.benchSizes.height = fo.height;
    fo.benchSizes.scalingShadowMapSize = std::min(fo.benchSizes.shadowMapSize, 1024);
    fo.command = givenCommandLine(*cmd);
    runFigures(*o);
  });
}

}  // namespace penumbra::cli
