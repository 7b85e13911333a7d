// penumbra inside someone else's renderer: filter the host's depth map into a technique's
// shadow map, then sample it from the host's own fragment shader with penumbraShadow()
// (docs/integration.md). The renderer's own frames go through the same class.
//
//   penumbra::gl::ShadowFilter filter;                  // on the host's current GL 4.5 context
//   filter.filter({.texture = hostDepth, .size = 2048}, settings);
//   filter.bind();                                      // before the host's draw
//   // host shader: #version 450, filter.shaderPreamble(), share/penumbra/glsl/penumbra_<id>.glsl,
//   // then   float v = penumbraShadow(shadowCoord);
//
// A guest's manners: filter() restores every GL state it changes (GlStateGuard lists them);
// it never reads the host's error queue or touches its debug callback unless the context is
// penumbra's own; it waits for nothing (no glFinish, read-back or query) unless timing was
// asked for with setTiming(true). params() after an LVSM Lloyd placement reads its splits back.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "penumbra/filter_mode.h"
#include "penumbra/filters.h"
#include "penumbra/technique.h"

namespace penumbra::gl {

// How the host's depth texture stores depth.
enum class DepthEncoding {
  // A depth-format texture (GL_DEPTH_COMPONENT16/24/32F, or with stencil) holding window depth
  // in [0, 1] through the light's projection: orthographic (linear already) or perspective
  // (hyperbolic; converted to linear depth along the light's axis with near and far).
  WindowDepth,
  // GL_R32F holding penumbra's linear depth metric in [0, 1] (penumbra/shared/light_depth.h).
  LinearDepth,
};

// The host's depth map: one 2D texture or a 2D array (cascades, a point light's six faces).
struct DepthInput {
  unsigned texture = 0;  // GL texture name, owned by the host
  int size = 0;          // texels per side (square maps)
  int layers = 1;        // 1 for GL_TEXTURE_2D; the layer count of a GL_TEXTURE_2D_ARRAY
  // Multisampled (GL_TEXTURE_2D_MULTISAMPLE_ARRAY, LinearDepth only): samples per texel.
  int samples = 1;
  DepthEncoding encoding = DepthEncoding::WindowDepth;
  // The light's projection (WindowDepth): whether it is perspective, and its near and far
  // planes; receivers' shadowCoord.z is then linearised the same way in penumbraShadow().
  bool perspective = false;
  float nearDistance = 0.0f;
  float farDistance = 1.0f;
};

struct FilterSettings {
  Technique technique = Technique::Vsm;
  TechniqueParams params = defaultTechniqueParams();
  BlurSpec blur{BlurKernel::Box, 2, 1.0f};  // prefilter; radius 0: none
  FilterMode filter = FilterMode::Bilinear;
  int anisotropy = 16;  // [1, 16], for the anisotropic filters
  // Encode and blur in one dispatch where it gives the same bits (RenderSettings::fusePrefilter:
  // off by default, docs/renderer.md).
  bool fusePrefilter = false;
  // Per layer, the prefilter's kernel and its width over layer 0's in texels (cascades keep
  // a kernel constant in world units). Empty: `blur` and 1 in every layer.
  std::vector<BlurSpec> layerBlurs;
  std::vector<float> layerKernelScales;
};

// Where bind() puts the shadow map, and the GLSL names them (shaderPreamble()). Defaults are
// the renderer's; a host moves any that collide with its own bindings.
struct ShadowBindings {
  int channelUnit = 0;      // sampler2DArray: the technique's channels (mips when filtered);
                            // left empty for PCF and the hard test, which read depthUnit
  int zmaxUnit = 1;         // ESM with the zmax classifier: its Z-max pyramid
  int depthUnit = 2;        // the unfiltered linear depth (ESM's fallback, PCF, the hard test)
  int parameterBlock = 0;   // uniform block: TechniqueParams
  int layerRangeBlock = 1;  // uniform block: the encode's texel-layer ranges
  int lookupBlock = 2;      // uniform block: the lookup's settings (shared/lookup_block.h)
  int satStatsBuffer = 2;   // storage buffers: the summed-area table (filter "sat")
  int satSumsBuffer = 3;
  int blurWeightsBuffer = 4;  // storage buffer: the prefilter's cumulative weights
};

// Every byte filter() holds on the GPU.
struct FilterMemory {
  uint64_t channels = 0;       // the channel texture, mips included (none for PCF, hard)
  uint64_t scratch = 0;        // the separable blur's intermediate
  uint64_t summedArea = 0;     // summed-area sums and statistics
  uint64_t auxiliary = 0;      // ESM's Z-max pyramid, LVSM's Lloyd samples
  uint64_t importedDepth = 0;  // the host's window depth as linear R32F layers
  uint64_t blocks = 0;         // parameter, range and lookup blocks, blur weights
  uint64_t total() const {
    return channels + scratch + summedArea + auxiliary + importedDepth + blocks;
  }
};

// Wall-clock milliseconds per stage of the last filter() (setTiming(true) only: each stage is
// then bracketed by glFinish, so the host's frame waits).
struct FilterTimes {
  double import = 0.0, auxiliary = 0.0, encode = 0.0, prefilter = 0.0, mipsOrSat = 0.0;
  double total() const { return import + auxiliary + encode + prefilter + mipsOrSat; }
};

class ShadowFilter {
 public:
  // Needs a current OpenGL 4.5 core context; checks what every technique needs (compute
  // shaders and their limits, float render targets) and throws Error naming what is missing.
  ShadowFilter();
  ~ShadowFilter();
  ShadowFilter(const ShadowFilter&) = delete;
  ShadowFilter& operator=(const ShadowFilter&) = delete;

  // Checks settings against their ranges and this GL (the summed-area table needs
  // GL_ARB_gpu_shader_int64 and fp64; the input's format must be a depth or R32F texture of
  // the stated size), then filters: (import) -> encode -> prefilter -> mips or summed-area
  // table (+ ESM's Z-max pyramid, LVSM's Lloyd placement) for every layer; for PCF and the hard
  // test the import alone (their lookup reads the depth). GL state is as before.
  void filter(const DepthInput& depth, const FilterSettings& settings);
  // For the filtered reference, which reads raw depth only: makes the input the depth bind()
  // binds and the lookup block the reference's (every mip level the lookup may use), without
  // encoding or filtering anything.
  void prepareRawDepth(const DepthInput& depth, const FilterSettings& settings);

  // Binds the last filtered map to `bindings` for the host's draw (units, blocks, buffers) and
  // sets the channel texture's sampling for the filter mode. The one call that leaves state
  // changed: the bindings are its purpose.
  void bind(const ShadowBindings& bindings = {}) const;
  // The #define lines a host's fragment shader needs before penumbra's GLSL for the last
  // filter(): the technique, the variant (summed-area table, Z-max pyramid, MSAA depth) and
  // the bindings. Goes right after #version.
  std::string shaderPreamble(const ShadowBindings& bindings = {}) const;

  // The GL names behind bind(), owned by the filter and valid until the next filter() or
  // prepareRawDepth() (which may recreate them when the shape changes): for a host that binds
  // or inspects them itself. The channel texture is a 2D array of layers x channel layers
  // (docs/integration.md), 0 for PCF and the hard test, whose lookup reads the depth; the depth is
  // penumbra's linear metric in R32F layers (the host's own texture when it was given as a linear
  // 2D array); the Z-max pyramid is 0 unless ESM's zmax classifier built it.
  unsigned channelTexture() const;
  unsigned linearDepthTexture() const;
  unsigned zmaxTexture() const;

  FilterMemory memory() const;
  // The parameters in effect (EVSM's exponents clamped to their storage, LVSM's splits placed).
  // LVSM's Lloyd placement runs on the GPU: the first call after filter() reads its splits back
  // (80 bytes), waiting for the placement, so it needs the filter's context current (and on
  // penumbra's own context reports a GL error pending there); filter() itself waits for nothing.
  const TechniqueParams& params() const;
  int channelMipLevels() const;
  int layers() const;

  void setTiming(bool enabled);
  FilterTimes lastTimes() const;

  struct State;  // GL objects; src/gl/shadow_filter_state.h
  State& state() { return *state_; }
  const State& state() const { return *state_; }

 private:
  std::unique_ptr<State> state_;
};

}  // namespace penumbra::gl
