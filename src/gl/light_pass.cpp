// Light-pass targets and drawing.
#include "light_pass.h"

#include <epoxy/gl.h>

#include "material_programs.h"
#include "memory_plan.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "texture_readback.h"

namespace penumbra::gl {

LightPass::~LightPass() {
  release();
}

void LightPass::release() {
  if (!framebuffers_.empty()) {
    glDeleteFramebuffers(GLsizei(framebuffers_.size()), framebuffers_.data());
  }
  framebuffers_.clear();
}

void LightPass::prepare(const LightPassShape& shape) {
  if (shape == shape_ && !framebuffers_.empty()) return;
  release();
  shape_ = shape;
  const bool ms = shape.samples > 1;
  const GLenum target = ms ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_ARRAY;
  depth_ = Texture(target);
  depthBuffer_ = Texture(target);
  if (ms) {
    glTextureStorage3DMultisample(depth_.id(), shape.samples, GL_R32F, shape.size, shape.size,
                                  shape.cascades, GL_TRUE);
    glTextureStorage3DMultisample(depthBuffer_.id(), shape.samples, GL_DEPTH_COMPONENT32F,
                                  shape.size, shape.size, shape.cascades, GL_TRUE);
  } else {
    glTextureStorage3D(depth_.id(), 1, GL_R32F, shape.size, shape.size, shape.cascades);
    glTextureStorage3D(depthBuffer_.id(), 1, GL_DEPTH_COMPONENT32F, shape.size, shape.size,
                       shape.cascades);
  }
  framebuffers_.resize(size_t(shape.cascades));
  glCreateFramebuffers(GLsizei(framebuffers_.size()), framebuffers_.data());
  for (int layer = 0; layer < shape.cascades; ++layer) {
    const unsigned fb = framebuffers_[size_t(layer)];
    glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0, depth_.id(), 0, layer);
    glNamedFramebufferTextureLayer(fb, GL_DEPTH_ATTACHMENT, depthBuffer_.id(), 0, layer);
    if (glCheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw Error("the light-pass framebuffer is incomplete (R32F + D32F, " +
                  std::to_string(shape.samples) + " samples, layer " + std::to_string(layer) + ")");
    }
  }
  checkErrors("allocating the light pass");
}

void LightPass::render(ProgramCache& programs, const GpuScene& scene,
                       std::span<const LightLayerView> views, bool ditherTranslucent) {
  const MaterialPrograms variants(programs, scene, GpuScene::Meshes::Casters,
                                  "passes/light_depth.vert", "passes/light_depth.frag", {});
  glViewport(0, 0, shape_.size, shape_.size);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  if (multisampled()) glEnable(GL_MULTISAMPLE);
  const float far = 1.0f;  // nothing there: the far plane
  for (const unsigned fb : framebuffers_) {
    glClearNamedFramebufferfv(fb, GL_COLOR, 0, &far);
    glClearNamedFramebufferfi(fb, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  }
  timer.begin();
  for (int layer = 0; layer < shape_.cascades; ++layer) {
    const LightLayerView& view = views[size_t(layer)];
    variants.each([&](const Program& program) {
      program.set("lightViewFromWorld", view.lightFromWorld);
      program.set("lightClipFromView", view.clipFromLight);
      program.set("lightPerspective", view.perspective ? 1 : 0);
      program.set("lightNear", view.nearDistance);
      program.set("lightFar", view.farDistance);
    });
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffers_[size_t(layer)]);
    scene.draw(
        [&](const GpuScene::Material& material) {
          const Program& program = variants.forMaterial(material);
          program.use();
          setMaterialUniforms(program, material);
          program.set("alphaBlend", material.translucent && ditherTranslucent ? 1 : 0);
          // MSAA: a masked caster is tested per sample, so each sample's coverage follows the
          // texture's alpha edge (a per-pixel discard would drop or keep all samples at once).
          if (multisampled() && material.alphaCutoff >= 0.0f) {
            glEnable(GL_SAMPLE_SHADING);
            glMinSampleShading(1.0f);
          } else {
            glDisable(GL_SAMPLE_SHADING);
          }
        },
        GpuScene::Meshes::Casters);
  }
  glDisable(GL_SAMPLE_SHADING);
  timer.end();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkErrors("light pass");
}

void LightPass::checkLayer(int layer) const {
  if (layer < 0 || layer >= shape_.cascades) {
    throw Error("light-pass layer " + std::to_string(layer) + " is out of range [0, " +
                std::to_string(shape_.cascades - 1) + "]");
  }
}

Image LightPass::readDepth(int layer) const {
  if (multisampled()) throw Error("readDepthMap reads single-sampled light passes only");
  checkLayer(layer);
  Image image(shape_.size, shape_.size, 1);
  glGetTextureSubImage(depth_.id(), 0, 0, 0, layer, shape_.size, shape_.size, 1, GL_RED, GL_FLOAT,
                       GLsizei(image.data().size() * sizeof(float)), image.data().data());
  checkErrors("reading the light pass's depth");
  return image;
}

Image LightPass::readDepthSamples(ProgramCache& programs, int layer) const {
  if (!multisampled()) return readDepth(layer);
  checkLayer(layer);
  const int size = shape_.size, samples = shape_.samples;
  Texture perSample(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(perSample.id(), 1, GL_R32F, size, size, samples);
  const Program& copy = programs.compute("passes/depth_samples.comp", {});
  glProgramUniform2i(copy.id(), glGetUniformLocation(copy.id(), "size"), size, size);
  copy.set("layer", layer);
  copy.set("sampleCount", samples);
  glBindTextureUnit(0, depth_.id());
  glBindImageTexture(0, perSample.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  copy.dispatch((unsigned(size) + 7u) / 8u, (unsigned(size) + 7u) / 8u);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  return readTexture(perSample.id(), 0, size, size, samples, 1, GL_RED, false);
}

uint64_t LightPass::bytes() const {
  return lightPassBytes(shape_.size, shape_.samples) * uint64_t(shape_.cascades);
}

}  // namespace penumbra::gl
