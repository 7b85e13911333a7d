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
}

MipChainPass::~MipChainPass() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteVertexArrays(1, &vertexArray_);
}

void MipChainPass::reduce(const Program& reduce, const ParameterBlock& parameters,
                          const Texture& texture, unsigned format, int layers, int size,
                          int levels) {
  parameters.bind();
  reduce.use();
  glBindVertexArray(vertexArray_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glBindSampler(0, bilinear_.id());
  const GLint layerUniform = glGetUniformLocation(reduce.id(), "layer");
  for (int level = 0; level + 1 < levels; ++level) {
    const int source = std::max(1, size >> level);
    const int target = std::max(1, size >> (level + 1));
    const Texture view = Texture::view(texture, GL_TEXTURE_2D_ARRAY, format, level, 1, layers);
    glBindTextureUnit(0, view.id());
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "sourceSize"), source,
                       source);
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "targetSize"), target,
                       target);
    glViewport(0, 0, target, target);
    for (int layer = 0; layer < layers; ++layer) {
      glNamedFramebufferTextureLayer(framebuffer_, GL_COLOR_ATTACHMENT0, texture.id(), level + 1,
                                     layer);
      glProgramUniform1i(reduce.id(), layerUniform, layer);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glNamedFramebufferTextureLayer(framebuffer_, GL_COLOR_ATTACHMENT0, 0, 0, 0);
  glBindSampler(0, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
}

}  // namespace penumbra::gl
