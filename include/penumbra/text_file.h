// Writing a whole text file, with the failure reported rather than lost in a stream's state.
#pragma once

#include <filesystem>
#include <string_view>

namespace penumbra {

// Writes `text` to `path` (replacing a file of that name); throws Error naming the path.
void writeTextFile(const std::filesystem::path& path, std::string_view text);

}  // namespace penumbra
