// Camera-pass targets, uniforms and drawing.
#include "camera_pass.h"

#include <epoxy/gl.h>

#include <cmath>

#include "material_programs.h"
#include "memory_plan.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/shared/shading.h"
#include "shadow_filter_state.h"
#include "texture_readback.h"

namespace penumbra::gl {
namespace {

GLint location(const Program& p, const char* name) {
  return glGetUniformLocation(p.id(), name);
}

void setCascadeUniforms(const Program& program, const FrameGeometry& frame) {
  const CascadeFrame& c = frame.cascades;
  program.set("cascadeCount", c.count);
  glProgramUniform4fv(program.id(), location(program, "cascadeBoxes"), c.count, &c.boxes[0][0]);
  std::vector<float> texel;
  for (int i = 0; i < c.count; ++i) {
    texel.push_back(frame.cascaded ? c.texelWorldSize(i, frame.shadowMapSize)
                                   : frame.lightView.texelWorldSize(frame.shadowMapSize));
  }
  glProgramUniform1fv(program.id(), location(program, "cascadeTexelWorldSize"), c.count,
                      texel.data());
  program.set("cascadeStart", c.start);
  glProgramUniform4fv(program.id(), location(program, "cascadeEnds0"), 1, &c.ends[0]);
  glProgramUniform4fv(program.id(), location(program, "cascadeEnds1"), 1, &c.ends[4]);
  program.set("cascadeBlendBand", c.blendBand);
}

// The camera and light uniforms the camera pass and its minimal lookup share.
void setViewUniforms(const Program& program, const RenderSettings& settings,
                     const FrameGeometry& frame, float aspect) {
  program.set("clipFromWorld",
              clipFromView(frame.camera, aspect, frame.viewBounds) * viewFromWorld(frame.camera));
  program.set("lightViewFromWorld", frame.lightView.lightFromWorld);
  program.set("lightClipFromView", frame.lightView.clipFromLight);
  program.set("lightNear", frame.lightView.nearDistance);
  program.set("lightFar", frame.lightView.farDistance);
  program.set("lightDirection", glm::normalize(frame.light.direction));
  program.set("lightPosition", frame.light.position);
  program.set("ambient", settings.ambient);
}

}  // namespace

CameraPass::~CameraPass() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  if (minimalFramebuffer_ != 0) glDeleteFramebuffers(1, &minimalFramebuffer_);
}

void CameraPass::prepare(int width, int height, bool diagnostics, bool lookupInputs) {
  diagnostics = diagnostics || lookupInputs;
  if (framebuffer_ != 0 && width == width_ && height == height_ && diagnostics == diagnostics_ &&
      lookupInputs == lookupInputs_) {
    return;
  }
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  width_ = width;
  height_ = height;
  diagnostics_ = diagnostics;
  lookupInputs_ = lookupInputs;
  struct Target {
    Texture* texture;
    GLenum format;
  };
  // Colour, then visibility and diagnostic, then the lookup's inputs (locations 1-2 and 3-6 in
  // camera.frag), as many as colorTargetCount().
  const Target targets[] = {{&color_, GL_RGBA16F},       {&visibility_, GL_R32F},
                            {&diagnostic_, GL_R32F},     {&lookup_, GL_RGBA32F},
                            {&receiverPlane_, GL_RG32F}, {&derivatives_, GL_RGBA32F},
                            {&cascade_, GL_RG32F}};
  const int count = colorTargetCount();
  for (int i = 0; i < 7; ++i) {
    *targets[i].texture = Texture();  // releases an earlier frame's
    if (i >= count) continue;
    *targets[i].texture = Texture(GL_TEXTURE_2D);
    glTextureStorage2D(targets[i].texture->id(), 1, targets[i].format, width, height);
  }
  depth_ = Texture(GL_TEXTURE_2D);
  glTextureStorage2D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
  glCreateFramebuffers(1, &framebuffer_);
  GLenum buffers[7];
  for (int i = 0; i < count; ++i) {
    buffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
    glNamedFramebufferTexture(framebuffer_, buffers[i], targets[i].texture->id(), 0);
  }
  glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  glNamedFramebufferDrawBuffers(framebuffer_, count, buffers);
  if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw Error("the camera-pass framebuffer is incomplete");
  }
  checkErrors("allocating the camera pass");
}

void CameraPass::render(ProgramCache& programs, const GpuScene& scene,
                        const RenderSettings& settings, const FrameGeometry& frame,
                        const ShadowFilter& shadows, bool reference) {
  // The lookup's variant and bindings are the filter's, as a host's shader gets them.
  std::vector<ShaderDefine> defines = lookupVariantDefines(shadows.state(), reference);
  for (const ShaderDefine& d : lookupParameterDefines(shadows.state())) defines.push_back(d);
  defines.push_back({"REFERENCE", reference ? "1" : "0"});
  defines.push_back({"LIGHT_PERSPECTIVE", frame.lightView.perspective ? "1" : "0"});
  defines.push_back({"POINT_LIGHT", frame.pointLight ? "1" : "0"});
  defines.push_back({"CASCADED", frame.cascaded ? "1" : "0"});
  defines.push_back({"SOFT_LIGHT", frame.light.size > 0.0f ? "1" : "0"});
  defines.push_back({"DIAGNOSTICS", diagnostics_ ? "1" : "0"});
  defines.push_back({"LOOKUP_INPUTS", lookupInputs_ ? "1" : "0"});
  defines.push_back({"CASCADE_OVERLAY", settings.overlay == Overlay::Cascades ? "1" : "0"});
  const MaterialPrograms variants(programs, scene, GpuScene::Meshes::All, "passes/camera.vert",
                                  "passes/camera.frag", defines);
  const float aspect = float(width_) / float(height_);
  variants.each([&](const Program& program) {
    setViewUniforms(program, settings, frame, aspect);
    setCascadeUniforms(program, frame);
    program.set("cameraViewFromWorld", viewFromWorld(frame.shadowCamera));
    const glm::vec3 axis = frame.light.target - frame.light.position;
    program.set("spotAxis", glm::length(axis) > 0.0f ? glm::normalize(axis) : glm::vec3(0, 0, -1));
    program.set("pointLightTangent", frame.pointFaceTangent);
    program.set("spotCosine", std::cos(glm::radians(0.5f * frame.light.spotAngleDegrees)));
    program.set("normalOffsetTexels", settings.normalOffsetTexels);
    program.set("lightSize", frame.light.size);
  });
  shadows.bind();
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width_, height_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  const float sky[4] = {shaders::kSkyColour.r, shaders::kSkyColour.g, shaders::kSkyColour.b, 1.0f};
  const float lit[4] = {1.0f, 0.0f, 0.0f, 0.0f};
  const float nothing[4] = {-1.0f, 0.0f, 0.0f, 0.0f};
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  // Every target, every frame: they live across frames, and pixels nothing covers this frame
  // must not keep the last frame's lookup.
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, sky);
  if (diagnostics_) {
    glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 1, lit);
    glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 2, nothing);
  }
  if (lookupInputs_) {
    for (int target = 3; target <= 5; ++target) {
      glClearNamedFramebufferfv(framebuffer_, GL_COLOR, target, zero);
    }
    glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 6, nothing);
  }
  glClearNamedFramebufferfi(framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  timer.begin();
  scene.draw([&](const GpuScene::Material& material) {
    const Program& program = variants.forMaterial(material);
    program.use();
    setMaterialUniforms(program, material);
    setCameraFaceCulling(material);
  });
  glDisable(GL_CULL_FACE);
  timer.end();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkErrors("camera pass");
}

void CameraPass::renderMinimalLookup(ProgramCache& programs, const GpuScene& scene,
                                     const RenderSettings& settings, const FrameGeometry& frame,
                                     const ShadowFilter& shadows, int layers, bool esmFallback) {
  if (frame.cascaded || frame.pointLight) {
    throw Error("the minimal lookup runs on one map: no cascades, no point light");
  }
  if (minimalFramebuffer_ == 0 || minimalWidth_ != width_ || minimalHeight_ != height_) {
    if (minimalFramebuffer_ != 0) glDeleteFramebuffers(1, &minimalFramebuffer_);
    minimalWidth_ = width_;
    minimalHeight_ = height_;
    minimalColor_ = Texture(GL_TEXTURE_2D);
    glTextureStorage2D(minimalColor_.id(), 1, GL_RGBA8, width_, height_);
    minimalDepth_ = Texture(GL_TEXTURE_2D);
    glTextureStorage2D(minimalDepth_.id(), 1, GL_DEPTH_COMPONENT32F, width_, height_);
    glCreateFramebuffers(1, &minimalFramebuffer_);
    glNamedFramebufferTexture(minimalFramebuffer_, GL_COLOR_ATTACHMENT0, minimalColor_.id(), 0);
    glNamedFramebufferTexture(minimalFramebuffer_, GL_DEPTH_ATTACHMENT, minimalDepth_.id(), 0);
    if (glCheckNamedFramebufferStatus(minimalFramebuffer_, GL_FRAMEBUFFER) !=
        GL_FRAMEBUFFER_COMPLETE) {
      throw Error("the minimal lookup's framebuffer is incomplete");
    }
  }
  std::vector<ShaderDefine> defines = lookupVariantDefines(shadows.state(), false);
  defines.push_back({"LIGHT_PERSPECTIVE", frame.lightView.perspective ? "1" : "0"});
  defines.push_back({"LAYER_COUNT", std::to_string(layers)});
  defines.push_back({"WITH_ESM_FALLBACK", esmFallback ? "1" : "0"});
  // The parameters the production pass compiles in (ESM's filter space decides its channel's
  // reduction), and its channel arrays' size, 4 x layers.
  for (const ShaderDefine& d : lookupParameterDefines(shadows.state())) defines.push_back(d);
  const Program& program =
      programs.graphics("passes/camera.vert", "passes/minimal_lookup.frag", defines);
  shadows.bind();
  setViewUniforms(program, settings, frame, float(width_) / float(height_));
  program.use();
  glBindFramebuffer(GL_FRAMEBUFFER, minimalFramebuffer_);
  glViewport(0, 0, width_, height_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  const float sky[4] = {shaders::kSkyColour.r, shaders::kSkyColour.g, shaders::kSkyColour.b, 1.0f};
  glClearNamedFramebufferfv(minimalFramebuffer_, GL_COLOR, 0, sky);
  glClearNamedFramebufferfi(minimalFramebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  minimalTimer.setEnabled(true);
  minimalTimer.begin();
  scene.draw([&](const GpuScene::Material& material) {
    setMaterialUniforms(program, material);
    setCameraFaceCulling(material);
  });
  glDisable(GL_CULL_FACE);
  minimalTimer.end();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkErrors("minimal lookup");
  ++minimalDraws_[esmFallback ? 1 : 0];
}

Image CameraPass::readMinimalLookupColor() const {
  if (minimalFramebuffer_ == 0) throw Error("the minimal lookup has not been drawn");
  return readTexture(minimalColor_.id(), 0, minimalWidth_, minimalHeight_, 1, 4, GL_RGBA, true);
}

Image CameraPass::readColor() const {
  return readTexture(color_.id(), 0, width_, height_, 1, 4, GL_RGBA, true);
}
Image CameraPass::readVisibility() const {
  requireDiagnostics();
  return readTexture(visibility_.id(), 0, width_, height_, 1, 1, GL_RED, true);
}
Image CameraPass::readDiagnostic() const {
  requireDiagnostics();
  return readTexture(diagnostic_.id(), 0, width_, height_, 1, 1, GL_RED, true);
}
void CameraPass::requireDiagnostics() const {
  if (!diagnostics_) {
    throw Error(
        "the camera pass did not write its visibility and diagnostic: ask for either in "
        "RenderSettings::readBack");
  }
}
void CameraPass::requireLookupInputs() const {
  if (!lookupInputs_) {
    throw Error(
        "the camera pass did not write the lookup's inputs: set "
        "RenderSettings::lookupInputs");
  }
}

Image CameraPass::readLookup() const {
  requireLookupInputs();
  return readTexture(lookup_.id(), 0, width_, height_, 1, 4, GL_RGBA, true);
}
Image CameraPass::readReceiverPlane() const {
  requireLookupInputs();
  return readTexture(receiverPlane_.id(), 0, width_, height_, 1, 2, GL_RG, true);
}
Image CameraPass::readUvDerivatives() const {
  requireLookupInputs();
  return readTexture(derivatives_.id(), 0, width_, height_, 1, 4, GL_RGBA, true);
}
Image CameraPass::readDepth() const {
  return readTexture(depth_.id(), 0, width_, height_, 1, 1, GL_DEPTH_COMPONENT, true);
}
Image CameraPass::readCascades() const {
  requireLookupInputs();
  return readTexture(cascade_.id(), 0, width_, height_, 1, 2, GL_RG, true);
}

uint64_t CameraPass::measuredBytes() const {
  uint64_t bytes = 0;
  for (const Texture* t : {&color_, &visibility_, &diagnostic_, &lookup_, &receiverPlane_,
                           &derivatives_, &cascade_, &depth_}) {
    if (t->id() == 0) continue;  // not allocated for this frame's outputs
    GLint width = 0, height = 0, bits = 0;
    glGetTextureLevelParameteriv(t->id(), 0, GL_TEXTURE_WIDTH, &width);
    glGetTextureLevelParameteriv(t->id(), 0, GL_TEXTURE_HEIGHT, &height);
    for (GLenum component : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE,
                             GL_TEXTURE_ALPHA_SIZE, GL_TEXTURE_DEPTH_SIZE}) {
      GLint size = 0;
      glGetTextureLevelParameteriv(t->id(), 0, component, &size);
      bits += size;
    }
    bytes += uint64_t(width) * uint64_t(height) * uint64_t(bits / 8);
  }
  checkErrors("measuring the camera pass's targets");
  return bytes;
}

uint64_t CameraPass::bytes() const {
  return frameBytes(width_, height_, diagnostics_, lookupInputs_);
}

}  // namespace penumbra::gl
