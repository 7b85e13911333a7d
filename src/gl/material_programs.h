// A mesh pass's program in two variants: ALPHA_TEST 0 for opaque meshes and ALPHA_TEST 1 for
// alpha-tested ones (lib/material.glsl). A fragment shader that may discard loses early depth
// testing, so with one program for both every hidden fragment of an opaque mesh would be shaded
// too (on llvmpipe the camera pass's largest cost over its minimal lookup, #28).
#pragma once

#include <string>
#include <vector>

#include "gpu_scene.h"
#include "program_cache.h"

namespace penumbra::gl {

class MaterialPrograms {
 public:
  // The alpha-tested variant is compiled only when a mesh `meshes` selects needs it.
  MaterialPrograms(ProgramCache& programs, const GpuScene& scene, GpuScene::Meshes meshes,
                   const std::string& vertex, const std::string& fragment,
                   const std::vector<ShaderDefine>& defines);

  // The variant that draws a mesh of this material.
  const Program& forMaterial(const GpuScene::Material& material) const;

  // Runs `set` on every compiled variant: the pass's uniforms other than the material's.
  template <class SetUniforms>
  void each(SetUniforms&& set) const {
    set(*opaque_);
    if (alphaTested_ != nullptr) set(*alphaTested_);
  }

 private:
  const Program* opaque_ = nullptr;
  const Program* alphaTested_ = nullptr;
};

}  // namespace penumbra::gl
