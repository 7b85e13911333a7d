// Shader variants by technique and defines; the parameter block.
#include "program_cache.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "penumbra/shared/layer_placement.h"
#include "penumbra/shared/technique_dispatch.h"

namespace penumbra::gl {
namespace {

// The Lloyd state as std430 lays it out (passes/lloyd_step.comp), copied from into the std140
// blocks: the splits first, the ranges at the next 16-byte boundary after the flags.
static_assert(offsetof(shaders::LloydState, splits) == 0);
static_assert(offsetof(shaders::LloydState, texelLayerRanges) == 96);
static_assert(sizeof(shaders::LloydState::texelLayerRanges) ==
              sizeof(shaders::TexelLayerRangeTable));
static_assert((offsetof(TechniqueParams, lvsm) + offsetof(shaders::LvsmParams, splits)) % 16 == 0,
              "std140 aligns the splits' vec4s to 16 bytes");

std::string variantKey(std::string key, const std::vector<ShaderDefine>& defines) {
  for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
  return key;
}

}  // namespace

bool ProgramCache::readsTechnique(std::string_view path) {
  auto found = readsTechnique_.find(path);
  if (found == readsTechnique_.end()) {
    const bool reads = library_.amalgamate(path).find("TECHNIQUE_ID") != std::string::npos;
    found = readsTechnique_.emplace(std::string(path), reads).first;
  }
  return found->second;
}

std::vector<ShaderDefine> ProgramCache::withTechnique(
    std::vector<ShaderDefine> defines, std::initializer_list<std::string_view> stages) {
  if (std::ranges::any_of(stages, [&](std::string_view s) { return readsTechnique(s); })) {
    defines.push_back({"TECHNIQUE_ID", std::to_string(int(technique_))});
  }
  return defines;
}

const Program& ProgramCache::graphics(const std::string& vertex, const std::string& fragment,
                                      const std::vector<ShaderDefine>& defines) {
  const std::vector<ShaderDefine> all = withTechnique(defines, {vertex, fragment});
  const std::string key = variantKey(vertex + "|" + fragment, all);
  auto found = programs_.find(key);
  if (found == programs_.end()) {
    found = programs_.emplace(key, Program::graphics(library_, vertex, fragment, all)).first;
  }
  return found->second;
}

const Program& ProgramCache::compute(const std::string& path,
                                     const std::vector<ShaderDefine>& defines) {
  const std::vector<ShaderDefine> all = withTechnique(defines, {path});
  const std::string key = variantKey(path, all);
  auto found = programs_.find(key);
  if (found == programs_.end()) {
    found = programs_.emplace(key, Program::compute(library_, path, all)).first;
  }
  return found->second;
}

ParameterBlock::ParameterBlock()
    : buffer_(sizeof(TechniqueParams)), ranges_(sizeof(shaders::TexelLayerRangeTable)) {}

void ParameterBlock::upload(Technique technique, const TechniqueParams& params) {
  // TechniqueParams mirrors a std140 block with explicit padding: bytewise equality is equality.
  if (valid_ && technique == technique_ && std::memcmp(&uploaded_, &params, sizeof params) == 0) {
    return;
  }
  glNamedBufferSubData(buffer_.id(), 0, sizeof params, &params);
  const shaders::TexelLayerRangeTable table = shaders::texelLayerRangeTable(int(technique), params);
  glNamedBufferSubData(ranges_.id(), 0, sizeof table, &table);
  technique_ = technique;
  uploaded_ = params;
  valid_ = true;
}

void ParameterBlock::copyPlacedSplits(const Buffer& lloydState) {
  using shaders::LloydState;
  glCopyNamedBufferSubData(lloydState.id(), buffer_.id(), offsetof(LloydState, splits),
                           offsetof(TechniqueParams, lvsm) + offsetof(shaders::LvsmParams, splits),
                           sizeof(shaders::LayerSplits));
  glCopyNamedBufferSubData(lloydState.id(), ranges_.id(), offsetof(LloydState, texelLayerRanges), 0,
                           sizeof(shaders::TexelLayerRangeTable));
  valid_ = false;
}

void ParameterBlock::bind(int parameterBinding, int rangeBinding) const {
  buffer_.bindUniform(unsigned(parameterBinding));
  ranges_.bindUniform(unsigned(rangeBinding));
}

}  // namespace penumbra::gl
