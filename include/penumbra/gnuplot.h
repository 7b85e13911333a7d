// Runs gnuplot (Debian's gnuplot-nox) on a script: plots come from a maintained plotting tool.
//
// Everything a script takes from outside (file and scene names, titles, paths) is data: it
// reaches gnuplot only as a single-quoted string literal, where gnuplot performs neither
// backquote command substitution nor macro expansion, and gnuplot is spawned without a shell.
// Its script, log and data files live in a private folder (mkdtemp, mode 0700) inside the
// folder the plot is written to, removed with everything in it when the plot is done.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

// A gnuplot string literal holding `text` for display: single quotes with `'` doubled; control
// characters (a line break would end the literal and start a new command) become '?'.
std::string gnuplotText(std::string_view text);

// A gnuplot string literal naming a file. The path is made absolute, so it can never begin with
// '|' or '<', which gnuplot's `set output` and `plot` would run as commands. Throws Error for a
// path holding control characters, which no literal can carry safely.
std::string gnuplotPath(const std::filesystem::path& path);

// gnuplotPath for the file a script writes (`set output`), listed first in the output folder's
// journal (output_journal.h) since gnuplot, not penumbra, creates it.
std::string gnuplotOutput(const std::filesystem::path& path);

// A batch of gnuplot figures: a private scratch folder inside `folder` (which must exist),
// removed with its contents by the destructor. A report adds its figures one by one and run()
// draws them all with a few gnuplot processes side by side: each start costs about 0.1 s
// (fonts, cairo), as much as drawing a heat map, and one process uses one core.
class GnuplotRun {
 public:
  // `processes`: at most this many gnuplot processes at once; 0: one per core, at most
  // kMaxProcesses.
  static constexpr int kMaxProcesses = 4;
  explicit GnuplotRun(const std::filesystem::path& folder, int processes = 0);
  ~GnuplotRun();
  GnuplotRun(const GnuplotRun&) = delete;
  GnuplotRun& operator=(const GnuplotRun&) = delete;

  // A path in the private folder for a data file the script reads (`name` a plain file name).
  std::filesystem::path scratchFile(std::string_view name) const;

  // Queues one figure's script (its own terminal and output). Each figure starts with `reset`,
  // which restores every plot setting but not linetypes (`set linetype`), user variables or
  // functions: a figure that sets those must not rely on an earlier one's or leave them to a
  // later one (plotCurves sets all it uses and is queued last).
  // `pixels`, the figure's canvas size, balances the processes: drawing time follows it.
  void add(const std::string& figure, double pixels = 1.0);
  // How many figures have been queued since this run began (names their scratch files apart).
  int figureCount() const { return figureCount_; }

  // Draws the queued figures (then none are pending) and waits for every process; throws Error
  // with gnuplot's own message when a process fails (the other processes' figures are drawn)
  // or gnuplot is not installed.
  void run();
  // add(script), then run().
  void run(const std::string& script);

 private:
  struct Figure {
    std::string script;
    double pixels;
  };
  std::filesystem::path scratch_;
  int processes_;
  std::vector<Figure> figures_;
  int figureCount_ = 0;
};

}  // namespace penumbra
