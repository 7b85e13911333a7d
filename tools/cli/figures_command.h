// `penumbra figures`: the seed papers' figures and tables regenerated into one HTML page.
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void registerFiguresCommand(CLI::App& app);

}  // namespace penumbra::cli
