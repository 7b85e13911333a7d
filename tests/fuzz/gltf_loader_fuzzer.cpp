// libFuzzer target: any bytes as a .gltf or .glb (no external files) must load or throw
// penumbra::Error, never crash, leak or hit undefined behaviour. Seeds: the glTF 2.0 files of
// Debian's assimp-testmodels (scripts/fuzz-loaders).
#include <cstddef>
#include <cstdint>
#include <span>

#include "gltf_loader.h"
#include "penumbra/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    penumbra::scene::loadGltf(std::span<const uint8_t>(data, size), "fuzz.gltf", "", false);
  } catch (const penumbra::Error&) {
    // a clean rejection
  }
  return 0;
}
