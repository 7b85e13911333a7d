// The opaque and alpha-tested variants of a mesh pass's program.
#include "material_programs.h"

#include "penumbra/error.h"

namespace penumbra::gl {

MaterialPrograms::MaterialPrograms(ProgramCache& programs, const GpuScene& scene,
                                   GpuScene::Meshes meshes, const std::string& vertex,
                                   const std::string& fragment,
                                   const std::vector<ShaderDefine>& defines) {
  auto variant = [&](const char* alphaTest) {
    std::vector<ShaderDefine> withTest = defines;
    withTest.push_back({"ALPHA_TEST", alphaTest});
    return &programs.graphics(vertex, fragment, withTest);
  };
  opaque_ = variant("0");
  if (scene.hasAlphaTested(meshes)) alphaTested_ = variant("1");
}

const Program& MaterialPrograms::forMaterial(const GpuScene::Material& material) const {
  if (!material.alphaTested()) return *opaque_;
  if (alphaTested_ == nullptr) {
    throw Error("an alpha-tested mesh outside the meshes its pass was prepared for");
  }
  return *alphaTested_;
}

}  // namespace penumbra::gl
