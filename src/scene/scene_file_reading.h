// Reading the files a scene consists of (the scene file, its buffers, images, material libraries
// and textures) as untrusted input: regular files only, their size charged to the load's memory
// budget before a byte is read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "memory_budget.h"

namespace penumbra::scene {

// The whole of the file at `path`, or nothing when it cannot be opened (missing, no permission):
// the caller decides whether that is fatal. Throws Error "<source>: <what> is not a regular file
// (...)" for a device, FIFO, socket or folder, which would never end or never start (it is opened
// without blocking, so a FIFO cannot stall the load), "<source>: <what> is ..., above the ...
// limit" when the budget cannot hold it, and "<source>: cannot read <what>" for a read error.
// `what` names the file in messages: "the scene file", "image 'a.png'".
std::optional<std::vector<uint8_t>> readSceneFile(const std::filesystem::path& path,
                                                  const std::string& what,
                                                  const std::string& source, MemoryBudget& budget);

}  // namespace penumbra::scene
