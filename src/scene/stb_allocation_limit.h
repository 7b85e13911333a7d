// A ceiling on each allocation stb_image makes while it decodes one image. The memory budget is
// charged from the image's header (width x height), but stb_image's inflate grows its buffer with
// the compressed stream, whatever the header says: a 255 KB PNG declaring 1x1 made it allocate
// 264 MB, and a 2 MB one would reach 2 GiB. decodeImage sets the ceiling from the header for the
// duration of one decode; an allocation beyond it fails, and stb_image reports out-of-memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>

namespace penumbra::scene {

struct StbAllocationLimit {
  size_t bytes = SIZE_MAX;  // the largest single allocation allowed now
  bool exceeded = false;    // an allocation was refused since the limit was set
};

inline thread_local StbAllocationLimit stbAllocationLimit;

inline void* stbLimitedMalloc(size_t size) {
  if (size > stbAllocationLimit.bytes) {
    stbAllocationLimit.exceeded = true;
    return nullptr;
  }
  return std::malloc(size);
}

inline void* stbLimitedRealloc(void* pointer, size_t size) {
  if (size > stbAllocationLimit.bytes) {
    stbAllocationLimit.exceeded = true;
    return nullptr;
  }
  return std::realloc(pointer, size);
}

}  // namespace penumbra::scene
