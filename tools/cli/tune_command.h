// `penumbra tune`: the setting of least error against the truth per scene and technique.
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void registerTuneCommand(CLI::App& app);

}  // namespace penumbra::cli
