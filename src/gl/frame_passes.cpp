// The light and camera passes and their render targets.
#include <epoxy/gl.h>

#include <cmath>

#include "gpu_scene.h"
#include "penumbra/error.h"
#include "penumbra/filters.h"
#include "penumbra/gl/context.h"
#include "renderer_state.h"
#include "shared/alpha_mask.h"
#include "shared/filter_weights.h"

namespace penumbra::gl {
namespace {

// A mesh's material for light_depth.frag and camera.frag (shared/alpha_mask.h).
void setMaterialUniforms(const Program& program, const Mesh& mesh) {
  program.set("baseColorAlpha", mesh.opacity);
  program.set("alphaCutoff", mesh.alphaTested() ? mesh.effectiveAlphaCutoff() : -1.0f);
  program.set("hasBaseColorTexture", mesh.baseColorTexture >= 0 ? 1 : 0);
}

void setChannelSampling(Renderer::State& s) {
  const FilterMode mode = s.settings.filter;
  const GLuint t = s.channels.id();
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, mode == FilterMode::Point ? GL_NEAREST : GL_LINEAR);
  GLint minFilter = GL_LINEAR;
  if (mode == FilterMode::Point) minFilter = GL_NEAREST;
  if (s.channelLevels > 1) minFilter = GL_LINEAR_MIPMAP_LINEAR;
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, minFilter);
  const float anisotropy = mode == FilterMode::Anisotropic ? float(s.settings.anisotropy) : 1.0f;
  glTextureParameterf(t, GL_TEXTURE_MAX_ANISOTROPY, anisotropy);
}

// The lookup's settings (shared/lookup_footprint.h LookupSettings) and its textures beyond the
// channels: the light pass's depth (ESM's fallback, the reference) and the blur's weights.
void setLookupUniforms(Renderer::State& s, const Program& program, bool reference) {
  const RenderSettings& settings = s.settings;
  const std::vector<float> cumulative = cumulativeBlurWeights(settings.blur);
  glProgramUniform1fv(program.id(), glGetUniformLocation(program.id(), "blurCumulative"),
                      GLsizei(cumulative.size()), cumulative.data());
  program.set("filterMode", int(settings.filter));
  program.set("shadowMapSize", s.shadowMapSize);
  // The reference follows the technique's lookup over every level the lookup may use.
  const int levels = reference && usesMips(settings.filter)
                         ? mipLevelCount(s.shadowMapSize, s.shadowMapSize)
                         : s.channelLevels;
  program.set("channelLevels", levels);
  program.set("anisotropy", settings.anisotropy);
  program.set("blurKernel", blurKernelId(settings.blur.kernel));
  program.set("blurRadius", settings.blur.radius);
  program.set("blurSigma", settings.blur.sigma);
  program.set("zmaxLevels", s.zmaxLevels);
  if (s.msaaSamples > 1) program.set("lightSamples", s.msaaSamples);
  glBindTextureUnit(2, s.lightDepth.id());
}

}  // namespace

void allocateLightPass(Renderer::State& s) {
  if (s.lightFramebuffer != 0) glDeleteFramebuffers(1, &s.lightFramebuffer);
  const bool ms = s.msaaSamples > 1;
  s.lightDepth = Texture(ms ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D);
  s.lightBuffer = Texture(ms ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D);
  if (ms) {
    glTextureStorage2DMultisample(s.lightDepth.id(), s.msaaSamples, GL_R32F, s.shadowMapSize,
                                  s.shadowMapSize, GL_TRUE);
    glTextureStorage2DMultisample(s.lightBuffer.id(), s.msaaSamples, GL_DEPTH_COMPONENT32F,
                                  s.shadowMapSize, s.shadowMapSize, GL_TRUE);
  } else {
    glTextureStorage2D(s.lightDepth.id(), 1, GL_R32F, s.shadowMapSize, s.shadowMapSize);
    glTextureStorage2D(s.lightBuffer.id(), 1, GL_DEPTH_COMPONENT32F, s.shadowMapSize,
                       s.shadowMapSize);
  }
  glCreateFramebuffers(1, &s.lightFramebuffer);
  glNamedFramebufferTexture(s.lightFramebuffer, GL_COLOR_ATTACHMENT0, s.lightDepth.id(), 0);
  glNamedFramebufferTexture(s.lightFramebuffer, GL_DEPTH_ATTACHMENT, s.lightBuffer.id(), 0);
  if (glCheckNamedFramebufferStatus(s.lightFramebuffer, GL_FRAMEBUFFER) !=
      GL_FRAMEBUFFER_COMPLETE) {
    throw Error("the light-pass framebuffer is incomplete (R32F + D32F, " +
                std::to_string(s.msaaSamples) + " samples)");
  }
}

void allocateFrame(Renderer::State& s, int width, int height) {
  if (s.frameFramebuffer != 0) glDeleteFramebuffers(1, &s.frameFramebuffer);
  s.frameColor = Texture(GL_TEXTURE_2D);
  s.frameVisibility = Texture(GL_TEXTURE_2D);
  s.frameDiagnostic = Texture(GL_TEXTURE_2D);
  s.frameLookup = Texture(GL_TEXTURE_2D);
  s.frameReceiverPlane = Texture(GL_TEXTURE_2D);
  s.frameDepth = Texture(GL_TEXTURE_2D);
  s.frameDerivatives = Texture(GL_TEXTURE_2D);
  glTextureStorage2D(s.frameColor.id(), 1, GL_RGBA8, width, height);
  glTextureStorage2D(s.frameVisibility.id(), 1, GL_R32F, width, height);
  glTextureStorage2D(s.frameDiagnostic.id(), 1, GL_R32F, width, height);
  glTextureStorage2D(s.frameLookup.id(), 1, GL_RGBA32F, width, height);
  glTextureStorage2D(s.frameReceiverPlane.id(), 1, GL_RG32F, width, height);
  glTextureStorage2D(s.frameDerivatives.id(), 1, GL_RGBA32F, width, height);
  glTextureStorage2D(s.frameDepth.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
  glCreateFramebuffers(1, &s.frameFramebuffer);
  glNamedFramebufferTexture(s.frameFramebuffer, GL_COLOR_ATTACHMENT0, s.frameColor.id(), 0);
  glNamedFramebufferTexture(s.frameFramebuffer, GL_COLOR_ATTACHMENT1, s.frameVisibility.id(), 0);
  glNamedFramebufferTexture(s.frameFramebuffer, GL_COLOR_ATTACHMENT2, s.frameDiagnostic.id(), 0);
  glNamedFramebufferTexture(s.frameFramebuffer, GL_COLOR_ATTACHMENT3, s.frameLookup.id(), 0);
  glNamedFramebufferTexture(s.frameFramebuffer, GL_COLOR_ATTACHMENT4, s.frameReceiverPlane.id(), 0);
  glNamedFramebufferTexture(s.frameFramebuffer, GL_COLOR_ATTACHMENT5, s.frameDerivatives.id(), 0);
  glNamedFramebufferTexture(s.frameFramebuffer, GL_DEPTH_ATTACHMENT, s.frameDepth.id(), 0);
  const GLenum buffers[6] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                             GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4, GL_COLOR_ATTACHMENT5};
  glNamedFramebufferDrawBuffers(s.frameFramebuffer, 6, buffers);
  if (glCheckNamedFramebufferStatus(s.frameFramebuffer, GL_FRAMEBUFFER) !=
      GL_FRAMEBUFFER_COMPLETE) {
    throw Error("the camera-pass framebuffer is incomplete");
  }
}

void renderLightPass(Renderer::State& s, const GpuScene& gpuScene, const LightView& light) {
  const Program& program = s.graphics("passes/light_depth.vert", "passes/light_depth.frag", {});
  program.set("lightViewFromWorld", light.lightFromWorld);
  program.set("lightClipFromView", light.clipFromLight);
  program.set("lightPerspective", light.perspective ? 1 : 0);
  program.set("lightNear", light.nearDistance);
  program.set("lightFar", light.farDistance);
  program.use();
  glBindFramebuffer(GL_FRAMEBUFFER, s.lightFramebuffer);
  glViewport(0, 0, s.shadowMapSize, s.shadowMapSize);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  if (s.msaaSamples > 1) glEnable(GL_MULTISAMPLE);
  const float far = 1.0f;  // nothing there: the far plane
  glClearNamedFramebufferfv(s.lightFramebuffer, GL_COLOR, 0, &far);
  glClearNamedFramebufferfi(s.lightFramebuffer, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  s.lightTimer.begin();
  gpuScene.draw(
      [&](const Mesh& mesh) {
        setMaterialUniforms(program, mesh);
        // MSAA: a masked caster is tested per sample, so each sample's coverage follows the
        // texture's alpha edge (per-pixel discard would drop or keep all samples at once).
        if (s.msaaSamples > 1 && mesh.alphaTested()) {
          glEnable(GL_SAMPLE_SHADING);
          glMinSampleShading(1.0f);
        } else {
          glDisable(GL_SAMPLE_SHADING);
        }
      },
      PENUMBRA_BASE_COLOR_TEXTURE_UNIT);
  glDisable(GL_SAMPLE_SHADING);
  s.lightTimer.end();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkErrors("light pass");
}

void renderCameraPass(Renderer::State& s, const Scene& scene, const GpuScene& gpuScene,
                      const LightView& light, bool reference) {
  const RenderSettings& settings = s.settings;
  const bool summedArea =
      !reference && settings.filter == FilterMode::SummedArea && s.satSums.has_value();
  const bool zmax = !reference && s.zmax.id() != 0;
  const Program& program = s.graphics("passes/camera.vert", "passes/camera.frag",
                                      {{"SUMMED_AREA", summedArea ? "1" : "0"},
                                       {"ZMAX", zmax ? "1" : "0"},
                                       {"MSAA", s.msaaSamples > 1 ? "1" : "0"},
                                       {"REFERENCE", reference ? "1" : "0"}});
  setLookupUniforms(s, program, reference);
  s.bindParameters();
  const float aspect = float(settings.width) / float(settings.height);
  program.set("clipFromWorld",
              clipFromView(scene.camera, aspect, scene.bounds()) * viewFromWorld(scene.camera));
  program.set("lightViewFromWorld", light.lightFromWorld);
  program.set("lightClipFromView", light.clipFromLight);
  program.set("lightPerspective", light.perspective ? 1 : 0);
  program.set("lightNear", light.nearDistance);
  program.set("lightFar", light.farDistance);
  program.set("lightDirection", glm::normalize(scene.light.direction));
  program.set("lightPosition", scene.light.position);
  program.set("spotAxis", glm::normalize(scene.light.target - scene.light.position));
  program.set("spotCosine", std::cos(glm::radians(0.5f * scene.light.spotAngleDegrees)));
  program.set("normalOffset", settings.normalOffsetTexels * light.texelWorldSize(s.shadowMapSize));
  program.set("texelWorldSize", light.texelWorldSize(s.shadowMapSize));
  program.set("ambient", settings.ambient);
  setChannelSampling(s);
  glBindTextureUnit(0, s.channels.id());
  if (zmax) glBindTextureUnit(1, s.zmax.id());
  if (summedArea) {
    s.satStats->bindStorage(2);
    s.satSums->bindStorage(3);
  }
  program.use();
  glBindFramebuffer(GL_FRAMEBUFFER, s.frameFramebuffer);
  glViewport(0, 0, settings.width, settings.height);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const float sky[4] = {0.62f, 0.72f, 0.86f, 1.0f};
  const float lit[4] = {1.0f, 0.0f, 0.0f, 0.0f};
  const float nothing[4] = {-1.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(s.frameFramebuffer, GL_COLOR, 0, sky);
  glClearNamedFramebufferfv(s.frameFramebuffer, GL_COLOR, 1, lit);
  glClearNamedFramebufferfv(s.frameFramebuffer, GL_COLOR, 2, nothing);
  glClearNamedFramebufferfi(s.frameFramebuffer, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  s.cameraTimer.begin();
  gpuScene.draw(
      [&](const Mesh& mesh) {
        program.set("albedo", mesh.albedo);
        setMaterialUniforms(program, mesh);
        // glTF doubleSided: false culls back faces from the camera (shadows are cast by both).
        if (mesh.doubleSided) {
          glDisable(GL_CULL_FACE);
        } else {
          glEnable(GL_CULL_FACE);
          glCullFace(GL_BACK);
        }
      },
      PENUMBRA_BASE_COLOR_TEXTURE_UNIT);
  glDisable(GL_CULL_FACE);
  s.cameraTimer.end();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkErrors("camera pass");
}

}  // namespace penumbra::gl
