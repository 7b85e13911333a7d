#include "mip_chain_pass.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "penumbra/gl/context.h"

namespace penumbra::gl {

MipChainPass::MipChainPass() {
  glCreateFramebuffers(1, &framebuffer_);
  glCreateVertexArrays(1, &vertexArray_);
}

MipChainPass::~MipChainPass() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteVertexArrays(1, &vertexArray_);
}

void MipChainPass::reduce(const MipReducePrograms& programs, const ParameterBlock& parameters,
                          const Texture& texture, int levels, int layers, int size) {
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
  for (int level = 0; level + 1 < levels; ++level) {
    const int source = std::max(1, size >> level);
    const int target = std::max(1, size >> (level + 1));
    const Program& reduce = source == 2 * target ? programs.halving : programs.general;
    reduce.use();
    glBindImageTexture(0, texture.id(), level, GL_TRUE, 0, GL_READ_ONLY, programs.format);
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "sourceSize"), source,
                       source);
    glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "targetSize"), target,
                       target);
    const GLint layerUniform = glGetUniformLocation(reduce.id(), "layer");
    glViewport(0, 0, target, target);
    for (int layer = 0; layer < layers; ++layer) {
      glNamedFramebufferTextureLayer(framebuffer_, GL_COLOR_ATTACHMENT0, texture.id(), level + 1,
                                     layer);
      glProgramUniform1i(reduce.id(), layerUniform, layer);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glNamedFramebufferTextureLayer(framebuffer_, GL_COLOR_ATTACHMENT0, 0, 0, 0);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, programs.format);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

}  // namespace penumbra::gl
