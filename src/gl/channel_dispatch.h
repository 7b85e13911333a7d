// What every compute pass over channel textures does the same way: 8x8 groups, the format's
// image qualifier as CHANNEL_FORMAT, the channel image at binding 0, square sizes as ivec2.
#pragma once

#include <vector>

#include "penumbra/channel_layout.h"
#include "penumbra/filters.h"
#include "penumbra/gl/program.h"
#include "program_cache.h"

namespace penumbra::gl {

inline constexpr unsigned kChannelGroup = 8;

inline unsigned groups(int n, unsigned size) {
  return (unsigned(n) + size - 1) / size;
}

// The encode and its minimal kernel (passes/encode.comp, passes/baseline_copy.comp) encode
// several texels of a column per invocation, a group's height apart (ROWS_PER_INVOCATION): on
// llvmpipe an invocation pays for every uniform it reads, and the encode reads the range block
// once per texel layer for all its rows. Four rows where a texel's layers take at most 8 bytes,
// else two: the encodes of EVSM4 and the power CDF (16 bytes) and CSM (32) ran slower with four
// than with two, where VSM's, ESM's and MSM's ran faster
// (docs/results/passes-llvmpipe-2026-12-06-rows.md). A group covers kChannelGroup x
// kChannelGroup * rows texels.
int encodeRowsPerInvocation(const ChannelLayout& layout);
ShaderDefine encodeRowsDefine(const ChannelLayout& layout);
// The encode's (and its minimal copy's) work groups over a size x size map.
struct GroupGrid {
  unsigned x = 0, y = 0;
};
GroupGrid encodeGroups(const ChannelLayout& layout, int size);

std::vector<ShaderDefine> formatDefines(const ChannelLayout& layout);
// How the blur and mip passes reduce the channels, resolved at compile time where possible
// (src/shaders/lib/layer_reduction.glsl): ALL_MEAN, or a one-layer LAYER_REDUCTIONS table.
std::vector<ShaderDefine> reductionDefines(Technique technique, const TechniqueParams& params,
                                           const ChannelLayout& layout);
void bindChannelImage(const Texture& texture, const ChannelLayout& layout, int level);
// One layer of a channel texture (level 0) as a 2D image at `unit`, GL_READ_ONLY or GL_WRITE_ONLY.
void bindChannelLayer(unsigned unit, const Texture& texture, const ChannelLayout& layout, int layer,
                      unsigned access);
// A blur kernel as compile-time constants: RADIUS and WEIGHTS (a GLSL float array of its 2r+1
// weights, each written as its exact bits). A loop bounded by a uniform radius, or layers by a
// uniform count, costs llvmpipe 1.4-2x the same loop of constant trip count
// (docs/results/passes-llvmpipe-2026-12-04.md); one program per kernel is cheap beside that.
// The minimal kernels and one map's prefilter passes take both; cascades' passes take RADIUS
// only (blurRadiusDefine: the fused pass) or neither (blur.comp), their weights as the uniform
// array `weights` (setBlurWeights): a cascade's Gaussian follows the view (blur.comp).
std::vector<ShaderDefine> blurKernelDefines(const BlurSpec& spec);
ShaderDefine blurRadiusDefine(const BlurSpec& spec);
// TAPS_ALIKE: 1 where the prefilter passes sum the kernel's taps at unit weight and scale the
// total once by weights[0] (sumsTapsAtUnitWeight, penumbra/filters.h), else 0.
ShaderDefine blurTapsAlikeDefine(const BlurSpec& spec, AlikeTaps alike);
void setBlurWeights(const Program& p, const BlurSpec& spec);
// The fused prefilter's work group, TILE x TILE texels (passes/prefilter_fused.comp, and its
// minimal kernel passes/baseline_fused.comp), and its shared arrays' components: TILE and
// TEXEL_COMPONENTS, the format's 1, 2 or 4.
inline constexpr int kFusedTile = 16;
std::vector<ShaderDefine> fusedTileDefines(const ChannelLayout& layout);
void setSize(const Program& p, const char* name, int size);

}  // namespace penumbra::gl
