// Fills a 2D-array texture's mip levels 1..n-1 from level 0 through the rasteriser: one draw per
// level and layer of passes/mip_reduce.frag, reading the level above as an image (a level never
// read while it is drawn). Owns its framebuffer and its empty vertex array.
#pragma once

#include "penumbra/gl/program.h"
#include "program_cache.h"

namespace penumbra::gl {

// The mip pass's two variants (passes/mip_reduce.frag): `halving` for the levels whose source is
// exactly twice the target (even sizes), `general` for odd sources; both read the source level
// as an image of the texture's own `format`.
struct MipReducePrograms {
  const Program& halving;
  const Program& general;
  unsigned format = 0;
};

class MipChainPass {
 public:
  MipChainPass();
  ~MipChainPass();
  MipChainPass(const MipChainPass&) = delete;
  MipChainPass& operator=(const MipChainPass&) = delete;

  // `texture`: `levels` levels of `layers` layers, level 0 `size` texels square.
  void reduce(const MipReducePrograms& programs, const ParameterBlock& parameters,
              const Texture& texture, int levels, int layers, int size);

 private:
  unsigned framebuffer_ = 0;
  unsigned vertexArray_ = 0;
};

}  // namespace penumbra::gl
