// Depth-only camera pass and its min/max reduction.
#include "depth_bounds_pass.h"

#include <cstring>
#include <limits>

#include "material_programs.h"
#include "memory_plan.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"

namespace penumbra::gl {

DepthBoundsPass::~DepthBoundsPass() {
  release();
}

void DepthBoundsPass::release() {
  forget();
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  framebuffer_ = 0;
  width_ = height_ = 0;
  depth_ = Texture();
  for (Slot& slot : slots_) {
    if (slot.buffer != 0) glDeleteBuffers(1, &slot.buffer);  // unmaps it
    slot = Slot{};
  }
}

void DepthBoundsPass::forget() {
  for (Slot& slot : slots_) {
    glDeleteSync(slot.fence);  // no sync (0) is ignored
    slot.fence = nullptr;
    slot.range.reset();
  }
  measured_ = 0;
}

uint64_t DepthBoundsPass::bytes() const {
  return framebuffer_ == 0 ? 0 : depthBoundsBytes(width_, height_);
}

void DepthBoundsPass::allocate(int width, int height) {
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
  // Persistently mapped and coherent: a finished measurement is read from memory, with no GL
  // call that could wait.
  const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  for (Slot& slot : slots_) {
    if (slot.buffer != 0) continue;
    glCreateBuffers(1, &slot.buffer);
    glNamedBufferStorage(slot.buffer, kDepthBoundsBytesPerMeasurement, nullptr, flags);
    slot.bits = static_cast<const uint32_t*>(
        glMapNamedBufferRange(slot.buffer, 0, kDepthBoundsBytesPerMeasurement, flags));
    if (slot.bits == nullptr) throw Error("the depth-bounds buffer could not be mapped");
  }
}

DepthRange DepthBoundsPass::collect(Slot& slot) {
  if (!slot.range) {
    GLenum status = glClientWaitSync(slot.fence, 0, 0);
    while (status == GL_TIMEOUT_EXPIRED) {
      status = glClientWaitSync(slot.fence, GL_SYNC_FLUSH_COMMANDS_BIT,
                                std::numeric_limits<GLuint64>::max());
    }
    if (status == GL_WAIT_FAILED) throw Error("waiting for the depth bounds failed");
    glDeleteSync(slot.fence);
    slot.fence = nullptr;
    if (slot.bits[1] == 0u) {
      slot.range = slot.projection;  // nothing drawn
    } else {
      DepthRange range;
      std::memcpy(&range.near, &slot.bits[0], 4);
      std::memcpy(&range.far, &slot.bits[1], 4);
      slot.range = range;
    }
  }
  return *slot.range;
}

DepthRange DepthBoundsPass::measure(ProgramCache& programs, const GpuScene& scene,
                                    const glm::mat4& clipFromWorld, DepthRange projection,
                                    int width, int height, bool wait) {
  if (framebuffer_ == 0 || width != width_ || height != height_) allocate(width, height);
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

  // This measurement takes the slot of the one before the previous.
  Slot& slot = slots_[size_t(measured_ % slots_.size())];
  Slot& previous = slots_[size_t((measured_ + slots_.size() - 1) % slots_.size())];
  glDeleteSync(slot.fence);
  slot.fence = nullptr;
  slot.range.reset();
  slot.projection = projection;
  const bool first = measured_++ == 0;
  // Positive floats order like their bit patterns: atomic min/max on the bits.
  const uint32_t start[2] = {0x7f7fffffu, 0u};
  glClearNamedBufferSubData(slot.buffer, GL_R32UI, 0, 4, GL_RED_INTEGER, GL_UNSIGNED_INT,
                            &start[0]);
  glClearNamedBufferSubData(slot.buffer, GL_R32UI, 4, 4, GL_RED_INTEGER, GL_UNSIGNED_INT,
                            &start[1]);
  const Program& reduce = programs.compute("passes/depth_bounds.comp", {});
  glProgramUniform2i(reduce.id(), glGetUniformLocation(reduce.id(), "size"), width, height);
  reduce.set("near", projection.near);
  reduce.set("far", projection.far);
  glBindTextureUnit(0, depth_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, slot.buffer);
  reduce.dispatch((unsigned(width) + 15u) / 16u, (unsigned(height) + 15u) / 16u);
  // The shader's writes made visible to the mapping before the fence signals.
  glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
  slot.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();  // the fence signals without another frame's flush
  checkErrors("measuring the depth bounds");

  return collect(wait || first ? slot : previous);
}

}  // namespace penumbra::gl
