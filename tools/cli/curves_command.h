// `penumbra curves`: shadow-test curves of every technique over receiver depth.
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void registerCurvesCommand(CLI::App& app);

}  // namespace penumbra::cli
