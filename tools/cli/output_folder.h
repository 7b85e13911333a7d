// The folder `render` and `curves` write their named files into: created when missing; files of
// the same names are replaced, nothing else in it is touched.
#pragma once

#include <filesystem>
#include <string>

namespace penumbra::cli {

// Throws Error for an empty path, which would put the files into the current folder unasked.
void checkOutputPath(const std::string& outDir);
// Checks the path and creates the folder; throws Error when it cannot be created.
std::filesystem::path createOutputFolder(const std::string& outDir);

}  // namespace penumbra::cli
