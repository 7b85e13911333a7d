// libFuzzer target: any bytes as an .obj, with the bytes after a NUL (if any) as every file it
// names (its .mtl libraries and textures), must load or throw penumbra::Error, never crash, leak
// or hit undefined behaviour, within a memory budget well under scripts/fuzz-loaders'
// -rss_limit_mb. Seeds: the OBJ files of Debian's assimp-testmodels.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_budget.h"
#include "obj_loader.h"
#include "penumbra/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto* split = static_cast<const uint8_t*>(std::memchr(data, 0, size));
  const size_t objSize = split ? size_t(split - data) : size;
  const std::string obj(reinterpret_cast<const char*>(data), objSize);
  const std::vector<uint8_t> other(split ? split + 1 : data + size, data + size);
  const penumbra::scene::ObjFileReader read =
      [&](const std::string&, const std::string&) -> std::optional<std::vector<uint8_t>> {
    if (!split) return std::nullopt;
    return other;
  };
  try {
    penumbra::scene::MemoryBudget budget(penumbra::fuzz::kMemoryBudgetBytes);
    penumbra::scene::loadObj(obj, "fuzz.obj", read, budget);
  } catch (const penumbra::Error&) {
    // a clean rejection
  }
  return 0;
}
