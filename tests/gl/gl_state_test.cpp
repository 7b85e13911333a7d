// GlStateGuard puts back what a guest changed on a host's context, and GlStateSnapshot, which
// the guard and the tests share, sees every change (a wider snapshot than the guard's).
#include "gl_state.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <array>
#include <optional>

#include "gl_test_context.h"
#include "penumbra/gl/context.h"

namespace penumbra {
namespace {

using gl::GlStateSnapshot;

// Units the tests record: twice the guard's, so a change past the guard's range shows.
constexpr int kTestedUnits = 2 * gl::kGlGuardedUnits;

class GlState : public testing::GlTest {};

// Objects for a host's state and a guest's, deleted with the test.
struct GlObjects {
  std::array<GLuint, 2> textures2d{}, textureArrays{}, buffers{}, vertexArrays{}, framebuffers{};
  std::array<GLuint, 2> samplers{}, programs{}, pipelines{}, renderbuffers{};
  GLint storageAlignment = 0;

  GlObjects(const GlObjects&) = delete;
  GlObjects& operator=(const GlObjects&) = delete;
  GlObjects() {
    glCreateTextures(GL_TEXTURE_2D, 2, textures2d.data());
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 2, textureArrays.data());
    for (int i = 0; i < 2; ++i) {
      glTextureStorage2D(textures2d[i], 1, GL_RGBA8, 4, 4);
      glTextureStorage3D(textureArrays[i], 1, GL_R32F, 4, 4, 2);
    }
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &storageAlignment);
    glCreateBuffers(2, buffers.data());
    for (GLuint b : buffers) glNamedBufferStorage(b, 4 * storageAlignment + 256, nullptr, 0);
    glCreateVertexArrays(2, vertexArrays.data());
    glCreateFramebuffers(2, framebuffers.data());
    glCreateSamplers(2, samplers.data());
    glCreateProgramPipelines(2, pipelines.data());
    glCreateRenderbuffers(2, renderbuffers.data());
    const char* source = "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    for (GLuint& p : programs) p = glCreateShaderProgramv(GL_COMPUTE_SHADER, 1, &source);
  }
  ~GlObjects() {
    glDeleteTextures(2, textures2d.data());
    glDeleteTextures(2, textureArrays.data());
    glDeleteBuffers(2, buffers.data());
    glDeleteVertexArrays(2, vertexArrays.data());
    glDeleteFramebuffers(2, framebuffers.data());
    glDeleteSamplers(2, samplers.data());
    glDeleteProgramPipelines(2, pipelines.data());
    glDeleteRenderbuffers(2, renderbuffers.data());
    for (GLuint p : programs) glDeleteProgram(p);
  }
};

// A host's state, unlike the defaults everywhere a guest could change it.
void setHostState(const GlObjects& o) {
  glUseProgram(o.programs[0]);
  glBindProgramPipeline(o.pipelines[0]);
  glBindVertexArray(o.vertexArrays[0]);
  const GLenum drawBuffers[] = {GL_NONE, GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT2};
  glNamedFramebufferDrawBuffers(o.framebuffers[0], 3, drawBuffers);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, o.framebuffers[0]);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, o.framebuffers[1]);
  glBindRenderbuffer(GL_RENDERBUFFER, o.renderbuffers[0]);
  glViewport(3, 4, 50, 60);
  glScissor(1, 2, 30, 40);
  glEnable(GL_SCISSOR_TEST);
  glEnable(GL_CULL_FACE);
  glDisable(GL_DITHER);
  glEnable(GL_BLEND);
  glDisablei(GL_BLEND, 1);
  glBlendFuncSeparatei(2, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
  glBlendEquationSeparatei(3, GL_MAX, GL_FUNC_SUBTRACT);
  glColorMaski(4, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  glDepthRange(0.25, 0.75);
  glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
  glCullFace(GL_FRONT);
  glFrontFace(GL_CW);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glPolygonOffset(2.0f, 3.0f);
  glMinSampleShading(0.5f);
  glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
  glClearDepth(0.5);
  glClearStencil(7);

  glBindTextureUnit(3, o.textures2d[0]);
  glBindTextureUnit(3, o.textureArrays[0]);  // a second target of the same unit
  glBindSampler(5, o.samplers[0]);
  glBindTextureUnit(7, o.textures2d[1]);
  glBindImageTexture(1, o.textureArrays[0], 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
  glBindImageTexture(4, o.textures2d[0], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glActiveTexture(GL_TEXTURE6);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, o.buffers[0]);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, o.buffers[1], o.storageAlignment, 64);
  // The generic bindings unlike the indexed ones bound last (which also set them).
  glBindBuffer(GL_UNIFORM_BUFFER, o.buffers[1]);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, o.buffers[0]);
  glBindBuffer(GL_ARRAY_BUFFER, o.buffers[0]);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, o.buffers[1]);
  glPixelStorei(GL_PACK_ALIGNMENT, 2);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
}

// What a guest might do: rebind or unbind every item, flip every switch, in units 0..7.
void changeEverything(const GlObjects& o) {
  glUseProgram(o.programs[1]);
  glBindProgramPipeline(o.pipelines[1]);
  glBindVertexArray(o.vertexArrays[1]);
  glNamedFramebufferDrawBuffer(o.framebuffers[0], GL_COLOR_ATTACHMENT1);  // the host's own
  glBindFramebuffer(GL_FRAMEBUFFER, o.framebuffers[1]);
  glNamedFramebufferReadBuffer(o.framebuffers[1], GL_COLOR_ATTACHMENT3);
  glBindRenderbuffer(GL_RENDERBUFFER, o.renderbuffers[1]);
  glViewport(0, 0, 8, 8);
  glScissor(0, 0, 8, 8);
  for (const gl::GlNamedEnum& capability : gl::kGlCapabilities) {
    (glIsEnabled(capability.value) ? glDisable : glEnable)(capability.value);
  }
  glDisable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDepthRange(0.0, 1.0);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glPolygonOffset(0.0f, 0.0f);
  glMinSampleShading(1.0f);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClearDepth(1.0);
  glClearStencil(0);

  for (GLuint unit = 0; unit < GLuint(gl::kGlGuardedUnits); ++unit) {
    glBindTextureUnit(unit, unit % 2 ? o.textures2d[1] : o.textureArrays[1]);
    glBindSampler(unit, o.samplers[1]);
    glBindImageTexture(unit, o.textures2d[1], 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
    glBindBufferRange(GL_UNIFORM_BUFFER, unit, o.buffers[1], 0, 16);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, unit, o.buffers[0]);
  }
  glBindImageTexture(2, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, 0);  // after glBindTextureUnit, one target alone
  for (const gl::GlBindingPoint& target : gl::kGlBufferTargets) {
    glBindBuffer(target.target, o.buffers[1]);
  }
  glBindBuffer(GL_UNIFORM_BUFFER, o.buffers[0]);  // the host's is buffers[1]
  for (const gl::GlNamedEnum& parameter : gl::kGlPixelStoreParameters) {
    glPixelStorei(parameter.value, 8);
  }
}

TEST_F(GlState, GuardRestoresEveryItemAGuestChanged) {
  const GlObjects objects;
  setHostState(objects);
  ASSERT_NO_THROW(gl::checkErrors("setting the host's state"));
  const GlStateSnapshot host = GlStateSnapshot::capture(kTestedUnits);
  {
    gl::GlStateGuard guard;
    changeEverything(objects);
    ASSERT_NO_THROW(gl::checkErrors("changing the state"));
    // The changes are seen: the comparison below is not vacuous.
    const std::string changed = host.differences(GlStateSnapshot::capture(kTestedUnits));
    for (const char* item :
         {"program:", "viewport:", "draw buffer 1:", "GL_DEPTH_TEST:",
          "texture unit 3 GL_TEXTURE_2D:", "texture unit 5 sampler:", "image unit 1:",
          "GL_UNIFORM_BUFFER binding 0:", "GL_SHADER_STORAGE_BUFFER binding 2:",
          "generic GL_UNIFORM_BUFFER binding:", "GL_PACK_ALIGNMENT:", "active texture:"}) {
      EXPECT_NE(changed.find(item), std::string::npos) << item << " not in\n" << changed;
    }
  }
  EXPECT_NO_THROW(gl::checkErrors("restoring the state"));
  const GlStateSnapshot restored = GlStateSnapshot::capture(kTestedUnits);
  EXPECT_TRUE(restored == host) << host.differences(restored);
}

TEST_F(GlState, GuardRestoresTheDefaultState) {
  const GlObjects objects;
  const GlStateSnapshot host = GlStateSnapshot::capture(kTestedUnits);
  {
    gl::GlStateGuard guard;
    changeEverything(objects);
  }
  EXPECT_NO_THROW(gl::checkErrors("restoring the state"));
  const GlStateSnapshot restored = GlStateSnapshot::capture(kTestedUnits);
  EXPECT_TRUE(restored == host) << host.differences(restored);
}

// Binds objects a guest will delete (penumbra's own, left bound by an earlier pass).
void bindDoomedObjects(const GlObjects& doomed) {
  glBindVertexArray(doomed.vertexArrays[0]);
  glBindFramebuffer(GL_FRAMEBUFFER, doomed.framebuffers[0]);
  glBindRenderbuffer(GL_RENDERBUFFER, doomed.renderbuffers[0]);
  glBindTextureUnit(2, doomed.textures2d[0]);
  glBindSampler(4, doomed.samplers[0]);
  glBindImageTexture(5, doomed.textureArrays[0], 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 3, doomed.buffers[0], doomed.storageAlignment, 64);
  glBindBufferBase(GL_UNIFORM_BUFFER, 1, doomed.buffers[1]);
  glBindBuffer(GL_ARRAY_BUFFER, doomed.buffers[1]);
}

TEST_F(GlState, GuardUnbindsObjectsDeletedMeanwhileAsGlWould) {
  const GlObjects host;
  setHostState(host);
  std::optional<GlObjects> doomed(std::in_place);
  bindDoomedObjects(*doomed);
  std::array<GLuint, 8> reused{};
  {
    gl::GlStateGuard guard;
    doomed.reset();
    // GL may give the freed names to objects of other targets.
    glCreateTextures(GL_TEXTURE_3D, GLsizei(reused.size()), reused.data());
  }
  EXPECT_NO_THROW(gl::checkErrors("restoring bindings of deleted objects"));
  const GlStateSnapshot restored = GlStateSnapshot::capture(kTestedUnits);
  glDeleteTextures(GLsizei(reused.size()), reused.data());

  // The same without a guard: GL's own unbinding on deletion.
  setHostState(host);
  doomed.emplace();
  bindDoomedObjects(*doomed);
  doomed.reset();
  const GlStateSnapshot deleted = GlStateSnapshot::capture(kTestedUnits);
  EXPECT_TRUE(restored == deleted) << deleted.differences(restored);

  // A current program outlives glDeleteProgram until a guest switches away from it.
  const char* source = "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
  const GLuint program = glCreateShaderProgramv(GL_COMPUTE_SHADER, 1, &source);
  glUseProgram(program);
  {
    gl::GlStateGuard guard;
    glUseProgram(0);
    glDeleteProgram(program);
  }
  EXPECT_NO_THROW(gl::checkErrors("restoring a deleted program"));
  EXPECT_EQ(GlStateSnapshot::capture().program, 0u);
}

TEST_F(GlState, SnapshotSeesChangesPastTheGuardsUnits) {
  const GlObjects objects;
  const GlStateSnapshot host = GlStateSnapshot::capture(kTestedUnits);
  {
    gl::GlStateGuard guard;  // units 0..7
    glBindTextureUnit(12, objects.textures2d[0]);
    glBindBufferBase(GL_UNIFORM_BUFFER, 9, objects.buffers[0]);
  }
  const std::string changed = host.differences(GlStateSnapshot::capture(kTestedUnits));
  EXPECT_NE(changed.find("texture unit 12 GL_TEXTURE_2D: 0 -> "), std::string::npos) << changed;
  EXPECT_NE(changed.find("GL_UNIFORM_BUFFER binding 9: (buffer 0, start 0, size 0) -> "),
            std::string::npos)
      << changed;
  EXPECT_EQ(changed.find("generic GL_UNIFORM_BUFFER binding: "), std::string::npos) << changed;
}

TEST_F(GlState, DifferencesNameEachItemWithBothValues) {
  const GlStateSnapshot before = GlStateSnapshot::capture();
  EXPECT_TRUE(before == GlStateSnapshot::capture());
  EXPECT_EQ(before.differences(before), "");
  glViewport(3, 4, 50, 60);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  const GlStateSnapshot after = GlStateSnapshot::capture();
  EXPECT_FALSE(before == after);
  const std::string changed = before.differences(after);
  EXPECT_NE(changed.find("viewport: (" + std::to_string(before.viewport[0])), std::string::npos)
      << changed;
  EXPECT_NE(changed.find(" -> (3, 4, 50, 60)\n"), std::string::npos) << changed;
  EXPECT_NE(changed.find("GL_DEPTH_TEST: false -> true\n"), std::string::npos) << changed;
  EXPECT_NE(changed.find("depth func: 0x0201 -> 0x0206\n"), std::string::npos) << changed;
}

}  // namespace
}  // namespace penumbra
