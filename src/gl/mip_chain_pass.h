// Fills a 2D-array texture's mip levels 1..n-1 from level 0 through the rasteriser: one draw per
// level and layer of passes/mip_reduce.frag, reading the level above through a one-level view
// (so the level being drawn is never the one sampled: no feedback loop). Owns its framebuffer,
// its empty vertex array and the bilinear sampler of the one-sample variants.
#pragma once

#include <span>
#include <vector>

#include "penumbra/gl/program.h"
#include "program_cache.h"

namespace penumbra::gl {

// One-level views of each of a 2D-array texture's `levels` levels (every layer), made once with
// the texture: the mip pass reads level l through views[l].
std::vector<Texture> levelViews(const Texture& texture, unsigned format, int levels, int layers);

// The mip pass's two variants (passes/mip_reduce.frag): `halving` for the levels whose source is
// exactly twice the target (even sizes), `general` for odd sources.
struct MipReducePrograms {
  const Program& halving;
  const Program& general;
  bool integerSource = false;  // the views are R32UI (packed RGBA8): read unfiltered
};

class MipChainPass {
 public:
  MipChainPass();
  ~MipChainPass();
  MipChainPass(const MipChainPass&) = delete;
  MipChainPass& operator=(const MipChainPass&) = delete;

  // `views` from levelViews(texture, ...): one per level.
  void reduce(const MipReducePrograms& programs, const ParameterBlock& parameters,
              const Texture& texture, std::span<const Texture> views, int layers, int size);

 private:
  unsigned framebuffer_ = 0;
  unsigned vertexArray_ = 0;
  // Bilinear within the one level a view holds, clamped to the edge (BILINEAR_MEAN's reads).
  Sampler bilinear_;
  // Integer views are incomplete under a linear filter: nearest for them (gathers ignore it).
  Sampler nearest_;
};

}  // namespace penumbra::gl
