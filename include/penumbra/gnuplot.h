// Runs gnuplot (Debian's gnuplot-nox) on a script: plots come from a maintained plotting tool.
#pragma once

#include <string>

namespace penumbra {

// Runs `gnuplot` on the script text; throws Error with gnuplot's own message when it fails or
// is not installed.
void runGnuplot(const std::string& script);

// Quotes text as a gnuplot string literal.
std::string gnuplotQuote(const std::string& text);

}  // namespace penumbra
