// `penumbra accuracy`: the accuracy gate's matrix of RMSE per scene and technique, checked
// against the ceilings table.
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void registerAccuracyCommand(CLI::App& app);

}  // namespace penumbra::cli
