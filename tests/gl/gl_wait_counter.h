// Counts calls of the GL entry points that wait for the GPU or read its results (glFinish, image,
// buffer and pixel reads, query results, fence waits: every one penumbra calls) while alive, and
// apart from them glGetError's (no wait on the GPU, but a guest must leave the host's errors
// alone).
#pragma once

#include <epoxy/gl.h>

#include "gl_call_swap.h"
#include "penumbra/gl/program.h"

namespace penumbra::testing {

// glClientWaitSync counts as a wait only with a timeout; with none it asks whether the fence has
// signalled and returns at once: a poll, counted apart.
class CountedSyncWaits {
 public:
  CountedSyncWaits(int& waits, int& polls) {
    real_ = epoxy_glClientWaitSync;
    waits_ = &waits;
    polls_ = &polls;
    epoxy_glClientWaitSync = &counted;
  }
  ~CountedSyncWaits() { epoxy_glClientWaitSync = real_; }
  CountedSyncWaits(const CountedSyncWaits&) = delete;
  CountedSyncWaits& operator=(const CountedSyncWaits&) = delete;

 private:
  static GLenum counted(GLsync sync, GLbitfield flags, GLuint64 timeout) {
    ++*(timeout > 0 ? waits_ : polls_);
    return real_(sync, flags, timeout);
  }
  static inline PFNGLCLIENTWAITSYNCPROC real_ = nullptr;
  static inline int* waits_ = nullptr;
  static inline int* polls_ = nullptr;
};

struct WaitCounter {
  static inline int waits = 0;
  static inline int polls = 0;  // glClientWaitSync without a timeout
  static inline int errorChecks = 0;

  // Calls each entry point once, so that libepoxy resolves it before the swap.
  static int resolve() {
    gl::Texture texture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), 1, GL_R32F, 1, 1);
    float texel = 0.0f;
    glGetTextureImage(texture.id(), 0, GL_RED, GL_FLOAT, sizeof texel, &texel);
    glGetTextureSubImage(texture.id(), 0, 0, 0, 0, 1, 1, 1, GL_RED, GL_FLOAT, sizeof texel, &texel);
    gl::Buffer buffer(16);
    glGetNamedBufferSubData(buffer.id(), 0, 4, &texel);
    // A framebuffer of its own: a surfaceless context's default one is incomplete.
    GLint bound = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &bound);
    GLuint framebuffer = 0;
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture.id(), 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadPixels(0, 0, 1, 1, GL_RED, GL_FLOAT, &texel);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(bound));
    glDeleteFramebuffers(1, &framebuffer);
    GLuint query = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &query);
    glBeginQuery(GL_TIME_ELAPSED, query);
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 result = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &result);
    glDeleteQueries(1, &query);
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    glDeleteSync(fence);
    glFinish();
    while (glGetError() != GL_NO_ERROR) {
    }
    waits = 0;
    polls = 0;
    errorChecks = 0;
    return 0;
  }

  int resolved = resolve();
  CountedGlCalls<&epoxy_glFinish> finish{waits};
  CountedGlCalls<&epoxy_glGetError> getError{errorChecks};
  CountedGlCalls<&epoxy_glGetTextureImage> getTextureImage{waits};
  CountedGlCalls<&epoxy_glGetTextureSubImage> getTextureSubImage{waits};
  CountedGlCalls<&epoxy_glGetNamedBufferSubData> getNamedBufferSubData{waits};
  CountedGlCalls<&epoxy_glReadPixels> readPixels{waits};
  CountedGlCalls<&epoxy_glGetQueryObjectui64v> getQueryObject{waits};
  CountedSyncWaits clientWaitSync{waits, polls};
};

}  // namespace penumbra::testing
