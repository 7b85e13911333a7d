// Which level-(l) texels one level-(l+1) texel reduces: the 2x2 block below it, and with an odd
// source size the last texel also takes the leftover row or column, so no texel is dropped. The
// GPU's mip pass, the CPU reference's reduceMipLevel and the filtered reference share it.
#ifndef PENUMBRA_SHARED_MIP_SPAN_H
#define PENUMBRA_SHARED_MIP_SPAN_H
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// Texels per side of a level: floor(size / 2^level), at least 1.
PENUMBRA_INLINE int mipLevelSize(int size, int level) {
  return max(size >> level, 1);
}

// [first, last] source texels (one axis) of destination texel i of `count`, from `sourceCount`.
PENUMBRA_INLINE ivec2 mipSourceSpan(int i, int count, int sourceCount) {
  int first = min(2 * i, sourceCount - 1);
  int last = i == count - 1 ? sourceCount - 1 : 2 * i + 1;
  return ivec2(first, last);
}

PENUMBRA_END_SHARED
#endif
