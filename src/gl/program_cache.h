// Compiled shader variants, built on first use and kept for the renderer's life. A variant whose
// source reads the technique (lib/technique_block.glsl) is specialised to the frame's technique
// (#define TECHNIQUE_ID) so its dispatcher folds to one branch (20x faster encode on llvmpipe
// than a run-time switch); one that does not (the light pass) is compiled once for all of them.
#pragma once

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/gl/program.h"
#include "penumbra/shader_library.h"
#include "penumbra/technique.h"

namespace penumbra::gl {

class ProgramCache {
 public:
  void setTechnique(Technique technique) { technique_ = technique; }
  const Program& graphics(const std::string& vertex, const std::string& fragment,
                          const std::vector<ShaderDefine>& defines);
  const Program& compute(const std::string& path, const std::vector<ShaderDefine>& defines);

 private:
  // The defines, with TECHNIQUE_ID where one of the stages reads it.
  std::vector<ShaderDefine> withTechnique(std::vector<ShaderDefine> defines,
                                          std::initializer_list<std::string_view> stages);
  bool readsTechnique(std::string_view path);

  ShaderLibrary library_;
  std::map<std::string, Program> programs_;
  std::map<std::string, bool, std::less<>> readsTechnique_;  // per stage's path
  Technique technique_ = Technique::Vsm;
};

// The technique's parameters as the std140 block every pass that runs shared math reads
// (binding 0), and the encode's per-texel-layer ranges derived from them (binding 1,
// shaders::texelLayerRangeTable); uploaded only when they change, so a warm frame uploads nothing.
class ParameterBlock {
 public:
  ParameterBlock();
  void upload(Technique technique, const TechniqueParams& params);
  // LVSM's splits and the encode's ranges for them from a Lloyd placement's state
  // (shaders::LloydState), copied on the GPU; the next upload() writes the whole block again.
  void copyPlacedSplits(const Buffer& lloydState);
  // Binds the parameters and the texel-layer ranges to these uniform-block bindings.
  void bind(int parameterBinding = 0, int rangeBinding = 1) const;
  uint64_t bytes() const { return buffer_.size() + ranges_.size(); }

 private:
  Buffer buffer_;
  Buffer ranges_;
  Technique technique_ = Technique::Vsm;
  TechniqueParams uploaded_{};
  bool valid_ = false;
};

}  // namespace penumbra::gl
