// Command-line options shared by subcommands that select techniques and set their parameters.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "penumbra/technique.h"

namespace penumbra::cli {

struct TechniqueOptions {
  std::string techniques = "all";
  std::vector<std::string> params;
};

// Adds --technique and --param to the subcommand.
void addTechniqueOptions(CLI::App& app, TechniqueOptions& options);

// True when --technique asked for the list; prints it.
bool printTechniqueListIfAsked(const TechniqueOptions& options);

// The selected techniques (ids, comma-separated, or "all") and their parameters; throws Error.
std::vector<Technique> selectedTechniques(const TechniqueOptions& options);
TechniqueParams selectedParams(const TechniqueOptions& options,
                               const std::vector<Technique>& techniques);

}  // namespace penumbra::cli
