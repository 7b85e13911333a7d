// The encode's minimal kernel in bench --passes (passes/baseline_copy.comp): the same read of a
// depth and the same writes to every channel layer, with the encode's texels per invocation, and
// no technique math. Layer l, component k of a texel holds depth x (1, 0.75, 0.5, 0.25)[k] +
// l / 16 (distinct values per component, as an encode's).
#pragma once

#include "penumbra/channel_layout.h"
#include "penumbra/gl/program.h"
#include "program_cache.h"

namespace penumbra::gl {

class MinimalCopy {
 public:
  MinimalCopy(ProgramCache& programs, const ChannelLayout& layout, int size);
  // depth: a size x size R32F array texture (layer 0 is read); channels: the layout's array
  // texture of that size, written at level 0.
  void run(const Texture& depth, const Texture& channels) const;

 private:
  const Program* program_;
  ChannelLayout layout_;
  int size_;
};

}  // namespace penumbra::gl
