// `penumbra bench`: performance experiments measured side by side in one run.
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void registerBenchCommand(CLI::App& app);

}  // namespace penumbra::cli
