// Every binding point penumbra's filter uses (units 0-2, blocks 0-2, storage 2-4, image units)
// holds a host object before the call; pixel pack and unpack buffers are bound, so a guest that
// uploads or reads back without unbinding them would go through the host's buffer.
#include "state_check.h"

#include <epoxy/gl.h>

#include <iostream>
#include <span>
#include <string>
#include <vector>

#include "gl_state_snapshot.h"

namespace {

void setUnusualState(const HostObjects& host, GLuint spareArray) {
  glUseProgram(host.program);
  glBindVertexArray(host.vertexArray);
  glBindFramebuffer(GL_FRAMEBUFFER, host.framebuffer);
  glViewport(3, 5, 77, 55);
  glEnable(GL_SCISSOR_TEST);
  glScissor(1, 2, 30, 40);
  glEnable(GL_BLEND);
  glEnable(GL_CULL_FACE);
  glDepthFunc(GL_LEQUAL);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  for (GLuint unit = 0; unit < 16; ++unit) {
    glBindTextureUnit(unit, host.depthTexture);  // GL_TEXTURE_2D
    glBindTextureUnit(unit, spareArray);         // GL_TEXTURE_2D_ARRAY
  }
  glActiveTexture(GL_TEXTURE7);
  for (GLuint unit = 0; unit < 4; ++unit) {
    glBindImageTexture(unit, spareArray, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA8);
  }
  for (GLuint i = 0; i < 8; ++i) {
    glBindBufferRange(GL_UNIFORM_BUFFER, i, host.buffer, 256 * i, 64);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, host.buffer, 256 * i, 128);
  }
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, host.buffer);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, host.buffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
}

// Keeps the GL errors the context reports (a debug context reports every one).
void GLAPIENTRY keepErrors(GLenum, GLenum type, GLuint, GLenum, GLsizei, const GLchar* text,
                           const void* errors) {
  if (type == GL_DEBUG_TYPE_ERROR) {
    static_cast<std::vector<std::string>*>(const_cast<void*>(errors))->push_back(text);
  }
}

}  // namespace

bool callKeepsHostState(const HostObjects& host, const std::function<void()>& call) {
  GLuint spareArray = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &spareArray);
  glTextureStorage3D(spareArray, 1, GL_RGBA8, 4, 4, 2);
  setUnusualState(host, spareArray);
  std::vector<std::string> errors;
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(keepErrors, &errors);
  while (glGetError() != GL_NO_ERROR) {
  }
  const std::span<const unsigned> textures(&host.depthTexture, 1);
  const GlStateSnapshot before = takeGlStateSnapshot(textures);
  glEnable(GL_TEXTURE_2D);  // the host's own error, left pending: GL_INVALID_ENUM in core GL

  call();

  const GLenum pending = glGetError(), next = glGetError();
  const std::string differences = describeDifferences(before, takeGlStateSnapshot(textures));
  glDebugMessageCallback(nullptr, nullptr);
  glDeleteTextures(1, &spareArray);
  // A debug context reports the host's error, and any the call made, to the host's callback.
  GLint flags = 0;
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  const size_t expectedErrors = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0 ? 1 : 0;
  const bool kept = differences.empty() && pending == GL_INVALID_ENUM && next == GL_NO_ERROR &&
                    errors.size() == expectedErrors;
  if (!kept) {
    std::cerr << "the call changed the host's GL state:\n"
              << differences << "error queue: 0x" << std::hex << pending << " then 0x" << next
              << std::dec << " (the host's 0x500, then 0x0 expected); " << errors.size()
              << " GL errors reported to the host's callback (" << expectedErrors
              << " expected: its own)\n";
    for (const std::string& e : errors) std::cerr << "  " << e << "\n";
  }
  std::cout << "host state " << (kept ? "kept" : "changed") << "\n";
  return kept;
}
