// `penumbra compare`: every technique against the exact references, as a report.
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void registerCompareCommand(CLI::App& app);

}  // namespace penumbra::cli
