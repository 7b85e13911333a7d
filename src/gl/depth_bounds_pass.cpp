// Depth-only camera pass and its min/max reduction.
#include "depth_bounds_pass.h"

#include <epoxy/gl.h>

#include <cstring>

#include "material_programs.h"
#include "memory_plan.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"

namespace penumbra::gl {

DepthBoundsPass::~DepthBoundsPass() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
}

void DepthBoundsPass::release() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  framebuffer_ = 0;
  width_ = height_ = 0;
  depth_ = Texture();
  bounds_.reset();
}

uint64_t DepthBoundsPass::bytes() const {
  return framebuffer_ == 0 ? 0 : depthBoundsBytes(width_, height_);
}

DepthRange DepthBoundsPass::measure(ProgramCache& programs, const GpuScene& scene,
                                    const glm::mat4& clipFromWorld, DepthRange projection,
                                    int width, int height, DepthRange fallback) {
  if (framebuffer_ == 0 || width != width_ || height != height_) {
    if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
    width_ = width;
    height_ = height;
    depth_ = Texture(GL_TEXTURE_2D);
    glTextureStorage2D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    glNamedFramebufferDrawBuffer(framebuffer_, GL_NONE);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw Error("the depth-bounds framebuffer is incomplete");
    }
    bounds_.emplace(2 * sizeof(uint32_t));
  }
  const MaterialPrograms variants(programs, scene, GpuScene::Meshes::All, "passes/camera.vert",
                                  "passes/depth_only.frag", {});
  variants.each([&](const Program& draw) { draw.set("clipFromWorld", clipFromWorld); });
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClearNamedFramebufferfi(framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  scene.draw([&](const GpuScene::Material& material) {  // what the camera pass will see
    const Program& draw = variants.forMaterial(material);
    draw.use();
    setMaterialUniforms(draw, material);
    setCameraFaceCulling(material);
  });
  glDisable(GL_CULL_FACE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  // Positive floats order like their bit patterns: atomic min/max on the bits.
  const uint32_t start[2] = {0x7f7fffffu, 0u};
  glClearNamedBufferSubData(bounds_->id(), GL_R32UI, 0, 4, GL_RED_INTEGER, GL_UNSIGNED_INT,
                            &start[0]);
  glClearNamedBufferSubData(bounds_->id(), GL_R32UI, 4, 4, GL_RED_INTEGER, GL_UNSIGNED_INT,
                            &start[1]);
  const Program& reduce = programs.compute("passes/depth_bounds.comp", {});
  glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "size"), width, height);
  reduce.set("near", projection.near);
  reduce.set("far", projection.far);
  glBindTextureUnit(0, depth_.id());
  bounds_->bindStorage(1);
  reduce.dispatch((unsigned(width) + 15u) / 16u, (unsigned(height) + 15u) / 16u);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t bits[2] = {0, 0};
  bounds_->read(std::as_writable_bytes(std::span(bits)));
  checkErrors("measuring the depth bounds");
  if (bits[1] == 0u) return fallback;  // nothing drawn
  DepthRange range;
  std::memcpy(&range.near, &bits[0], 4);
  std::memcpy(&range.far, &bits[1], 4);
  return range;
}

}  // namespace penumbra::gl
