// `penumbra render`: render a built-in scene with one or more techniques.
#pragma once

#include <CLI/CLI.hpp>

namespace penumbra::cli {

void registerRenderCommand(CLI::App& app);

}  // namespace penumbra::cli
