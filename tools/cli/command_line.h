// The command line a subcommand was given, rebuilt from what CLI11 parsed: recorded in outputs
// (the bench and figures pages) so that a result says how to reproduce it.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace penumbra::cli {

inline std::string givenCommandLine(const CLI::App& command) {
  std::string line = "penumbra " + command.get_name();
  for (const CLI::Option* opt : command.get_options()) {
    if (opt->count() == 0 || opt->get_name() == "--help") continue;
    line += " " + opt->get_name();
    if (opt->get_type_size() == 0) continue;  // a flag: its name is all
    for (const std::string& v : opt->results()) line += " " + v;
  }
  return line;
}

}  // namespace penumbra::cli
