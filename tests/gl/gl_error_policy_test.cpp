// Whose GL errors they are: on a host's context (CurrentContext, GlErrors::LeaveToHost) penumbra
// leaves the host's debug callback, debug switches and glGetError queue alone; on its own it
// reports them. The policy is per thread and returns to the one before when a context object goes.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <bit>

#include "gl_test_context.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"

namespace penumbra {
namespace {

class GlErrorPolicy : public testing::GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    while (glGetError() != GL_NO_ERROR) {
    }
  }
};

struct HostDebugLog {
  int messages = 0;
};

void GLAPIENTRY hostCallback(GLenum, GLenum, GLuint, GLenum, GLsizei, const GLchar*,
                             const void* user) {
  ++static_cast<HostDebugLog*>(const_cast<void*>(user))->messages;
}

GLDEBUGPROC currentCallback() {
  void* function = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &function);
  return std::bit_cast<GLDEBUGPROC>(function);
}

void* currentUserParameter() {
  void* user = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
  return user;
}

constexpr GLenum kNoSuchCapability = 0xFFFF;  // glEnable of it is GL_INVALID_ENUM

TEST_F(GlErrorPolicy, HostContextKeepsItsDebugCallbackAndErrorQueue) {
  static HostDebugLog log;  // outlives the context, which may call back until it is destroyed
  glDebugMessageCallback(hostCallback, &log);
  glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  const bool debugOutput = glIsEnabled(GL_DEBUG_OUTPUT);

  const gl::CurrentContext host;  // GlErrors::LeaveToHost
  EXPECT_EQ(currentCallback(), &hostCallback);
  EXPECT_EQ(currentUserParameter(), &log);
  EXPECT_FALSE(glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS));
  EXPECT_EQ(bool(glIsEnabled(GL_DEBUG_OUTPUT)), debugOutput);

  glEnable(kNoSuchCapability);
  EXPECT_NO_THROW(gl::checkErrors("x"));
  EXPECT_NO_THROW(gl::discardPendingErrors());
  EXPECT_EQ(glGetError(), GLenum(GL_INVALID_ENUM));  // still the host's to read
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlErrorPolicy, ReportingCurrentContextThrowsPendingErrors) {
  static HostDebugLog log;
  glDebugMessageCallback(hostCallback, &log);
  const gl::CurrentContext own(gl::GlErrors::Report);  // a window penumbra opened
  EXPECT_NE(currentCallback(), &hostCallback);
  EXPECT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS));
  glEnable(kNoSuchCapability);
  EXPECT_THROW(gl::checkErrors("x"), Error);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlErrorPolicy, PolicyOfTheContextBeforeReturnsWhenOneGoes) {
  {
    const gl::CurrentContext host;
    {
      const gl::CurrentContext own(gl::GlErrors::Report);
      glEnable(kNoSuchCapability);
      EXPECT_THROW(gl::checkErrors("inside the reporting context"), Error);
    }
    glEnable(kNoSuchCapability);
    EXPECT_NO_THROW(gl::checkErrors("back in the host's"));
  }
  // The test fixture's HeadlessContext reports again, the error the host left included.
  EXPECT_THROW(gl::checkErrors("back in penumbra's own"), Error);
  EXPECT_NO_THROW(gl::checkErrors("drained"));
}

}  // namespace
}  // namespace penumbra
