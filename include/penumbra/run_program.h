// Running an external tool (gnuplot, ffmpeg, glslangValidator) without a shell: the arguments
// reach the program as they are, so a file or scene name is never parsed as a command.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace penumbra {

struct ProgramResult {
  bool started = false;  // false when the program was not found on PATH or could not start
  int exitCode = -1;     // the program's exit status; -1 when it was killed by a signal
  bool succeeded() const { return started && exitCode == 0; }
};

// Runs `args[0]`, found on PATH, with exactly `args` (no shell) and waits for it. Its standard
// output and error go to `log`, created anew (O_EXCL, O_NOFOLLOW: a planted file or link there
// is refused, never written through), or, when `log` is empty, standard output goes to
// /dev/null and standard error is inherited. Throws Error when `log` cannot be created.
ProgramResult runProgram(const std::vector<std::string>& args,
                         const std::filesystem::path& log = {});

}  // namespace penumbra
