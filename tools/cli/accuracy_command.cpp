// `penumbra accuracy`: measures every technique on every built-in scene against the filtered
// reference (penumbra/compare/accuracy.h), prints the matrix, and checks it against a ceilings
// table or writes a new one.
#include "accuracy_command.h"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "penumbra/compare/accuracy.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "progress_bar.h"

namespace penumbra::cli {
namespace {

struct AccuracyOptions {
  std::string ceilings;       // check against this table
  std::string writeCeilings;  // write a table at `factor` x the measured values
  double factor = 1.25;
  bool quiet = false;
};

// The matrix as a Markdown table: one row per configuration and scene, techniques as columns
// ("-" where a configuration does not run a technique).
std::string matrixTable(const std::vector<compare::AccuracyEntry>& entries) {
  std::vector<std::string> techniques, rows;
  auto rowOf = [](const compare::AccuracyEntry& e) {
    return e.configuration == "default" ? e.scene : e.configuration + ": " + e.scene;
  };
  for (const auto& e : entries) {
    if (std::find(techniques.begin(), techniques.end(), e.technique) == techniques.end())
      techniques.push_back(e.technique);
    if (std::find(rows.begin(), rows.end(), rowOf(e)) == rows.end()) rows.push_back(rowOf(e));
  }
  std::ostringstream out;
  out << "| scene |";
  for (const auto& t : techniques) out << " " << t << " |";
  out << "\n| --- |";
  for (size_t i = 0; i < techniques.size(); ++i) out << " --- |";
  for (const std::string& row : rows) {
    out << "\n| " << row << " |";
    for (const std::string& t : techniques) {
      auto e = std::find_if(entries.begin(), entries.end(), [&](const compare::AccuracyEntry& x) {
        return rowOf(x) == row && x.technique == t;
      });
      if (e == entries.end()) {
        out << " - |";
      } else {
        out << " " << std::setprecision(3) << e->rmse << " |";
      }
    }
  }
  out << "\n";
  return out.str();
}

void runAccuracy(const AccuracyOptions& o) {
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  std::vector<compare::AccuracyCeiling> ceilings;
  if (!o.ceilings.empty()) ceilings = compare::readAccuracyCeilings(o.ceilings);
  std::vector<compare::AccuracyEntry> measured;
  {
    ProgressBar bar(o.quiet);
    measured = compare::measureAccuracy(
        renderer,
        [&](int done, int total, const std::string& step) { bar.update(done, total, step); });
  }
  std::cout << "RMSE against the filtered reference (" << renderer.deviceDescription() << "):\n"
            << matrixTable(measured);
  if (!o.writeCeilings.empty()) {
    if (!(o.factor >= 1.0 && o.factor <= 4.0)) {
      throw Error("ceiling factor " + std::to_string(o.factor) + " is out of range [1, 4]");
    }
    compare::writeAccuracyCeilings(compare::ceilingsFor(measured, o.factor, 1e-6), o.writeCeilings);
    std::cout << "wrote " << o.writeCeilings << "\n";
  }
  if (!o.ceilings.empty()) {
    const std::vector<std::string> problems = compare::checkAccuracy(measured, ceilings);
    for (const std::string& p : problems) std::cout << "FAIL " << p << "\n";
    if (!problems.empty()) {
      throw Error(std::to_string(problems.size()) + " of " + std::to_string(measured.size()) +
                  " entries break the accuracy ceilings in " + o.ceilings);
    }
    std::cout << "all " << measured.size() << " entries within their ceilings\n";
  }
}

}  // namespace

void registerAccuracyCommand(CLI::App& app) {
  auto o = std::make_shared<AccuracyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "accuracy",
      "The accuracy gate: RMSE of every technique on every built-in scene against the filtered "
      "reference at small sizes, and on one scene each under trilinear, anisotropic and "
      "summed-area lookups, a Gaussian blur, cascades and MSAA, checked against a ceilings "
      "table.");
  cmd->add_option("--ceilings", o->ceilings,
                  "check against this table (docs/results/accuracy-ceilings.csv); exit 1 when an "
                  "entry breaks its ceiling");
  cmd->add_option("--write-ceilings", o->writeCeilings,
                  "write a new table with ceilings at --factor x the measured RMSE");
  cmd->add_option("--factor", o->factor, "ceiling over the measured RMSE, 1..4")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar");
  cmd->callback([o] { runAccuracy(*o); });
}

}  // namespace penumbra::cli
