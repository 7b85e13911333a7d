// libFuzzer target: any bytes as a .gltf or .glb (no external files) must load or throw
// penumbra::Error, never crash, leak or hit undefined behaviour, within a memory budget well
// under scripts/fuzz-loaders' -rss_limit_mb (an allocation the budget does not foresee fails the
// run). Seeds: the glTF 2.0 files of Debian's assimp-testmodels and a deep node chain
// (scripts/fuzz-loaders).
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_budget.h"
#include "gltf_loader.h"
#include "penumbra/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    penumbra::scene::MemoryBudget budget(penumbra::fuzz::kMemoryBudgetBytes);
    penumbra::scene::loadGltf(std::span<const uint8_t>(data, size), "fuzz.gltf", "", false, budget);
  } catch (const penumbra::Error&) {
    // a clean rejection
  }
  return 0;
}
