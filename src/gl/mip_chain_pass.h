// Fills a 2D-array texture's mip levels 1..n-1 from level 0 through the rasteriser: one draw per
// level and layer of passes/mip_reduce.frag, reading the level above through a one-level view
// (so the level being drawn is never the one sampled: no feedback loop). Owns its framebuffer,
// its empty vertex array and the bilinear sampler of the one-sample mean variant.
#pragma once

#include "penumbra/gl/program.h"
#include "program_cache.h"

namespace penumbra::gl {

class MipChainPass {
 public:
  MipChainPass();
  ~MipChainPass();
  MipChainPass(const MipChainPass&) = delete;
  MipChainPass& operator=(const MipChainPass&) = delete;

  // `reduce` is passes/fullscreen.vert + passes/mip_reduce.frag with the texture's reduction
  // defines; `format` the texture's internal format (its views').
  void reduce(const Program& reduce, const ParameterBlock& parameters, const Texture& texture,
              unsigned format, int layers, int size, int levels);

 private:
  unsigned framebuffer_ = 0;
  unsigned vertexArray_ = 0;
  // Bilinear within the one level a view holds, clamped to the edge (BILINEAR_MEAN's reads).
  Sampler bilinear_;
};

}  // namespace penumbra::gl
