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

// One gnuplot process: a private scratch folder inside `folder` (which must exist), removed
// with its contents by the destructor. A report's figures are added one by one and drawn by one
// process: each gnuplot start costs about 0.1 s (fonts, cairo), most of a heat map's time.
class GnuplotRun {
 public:
  explicit GnuplotRun(const std::filesystem::path& folder);
  ~GnuplotRun();
  GnuplotRun(const GnuplotRun&) = delete;
  GnuplotRun& operator=(const GnuplotRun&) = delete;

  // A path in the private folder for a data file the script reads (`name` a plain file name).
  std::filesystem::path scratchFile(std::string_view name) const;

  // Queues one figure's script (its own terminal and output). Each figure starts from
  // gnuplot's defaults (`reset`), so no setting leaks from one figure into the next.
  void add(const std::string& figure);
  // How many figures have been queued since this run began (names their scratch files apart).
  int figureCount() const { return figures_; }

  // Writes the queued figures into the private folder as one script and runs gnuplot on it
  // once; throws Error with gnuplot's own message when it fails or is not installed.
  void run();
  // add(script), then run().
  void run(const std::string& script);

 private:
  std::filesystem::path scratch_;
  std::string script_;
  int figures_ = 0;
};

}  // namespace penumbra
