#include "mip_chain_pass.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "penumbra/gl/context.h"

namespace penumbra::gl {

MipChainPass::MipChainPass() {
  glCreateFramebuffers(1, &framebuffer_);
  glCreateVertexArrays(1, &vertexArray_);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(bilinear_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

MipChainPass::~MipChainPass() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteVertexArrays(1, &vertexArray_);
}

std::vector<Texture> levelViews(const Texture& texture, unsigned format, int levels, int layers) {
  std::vector<Texture> views;
  for (int level = 0; level < levels; ++level) {
    views.push_back(Texture::view(texture, GL_TEXTURE_2D_ARRAY, format, level, 1, layers));
  }
  return views;
}

void MipChainPass::reduce(const MipReducePrograms& programs, const ParameterBlock& parameters,
                          const Texture& texture, std::span<const Texture> views, int layers,
                          int size) {
  parameters.bind();
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glBindVertexArray(vertexArray_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  // Each texel written as computed: no depth test, blending, scissor, culling, or dithering (GL
  // may dither unorm colour writes; image stores never are).
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DITHER);
  glBindSampler(0, programs.integerSource ? nearest_.id() : bilinear_.id());
  for (size_t level = 0; level + 1 < views.size(); ++level) {
    const int source = std::max(1, size >> level);
    const int target = std::max(1, size >> (level + 1));
    const Program& reduce = source == 2 * target ? programs.halving : programs.general;
    reduce.use();
    glBindTextureUnit(0, views[level].id());
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "sourceSize"), source,
                       source);
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "targetSize"), target,
                       target);
    const GLint layerUniform = glGetUniformLocation(reduce.id(), "layer");
    glViewport(0, 0, target, target);
    for (int layer = 0; layer < layers; ++layer) {
      glNamedFramebufferTextureLayer(framebuffer_, GL_COLOR_ATTACHMENT0, texture.id(),
                                     GLint(level) + 1, layer);
      glProgramUniform1i(reduce.id(), layerUniform, layer);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glNamedFramebufferTextureLayer(framebuffer_, GL_COLOR_ATTACHMENT0, 0, 0, 0);
  glBindSampler(0, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

}  // namespace penumbra::gl
