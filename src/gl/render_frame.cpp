// One frame: depth bounds -> light pass per cascade -> auxiliary passes -> encode -> prefilter
// -> camera pass (or the filtered reference), and the read-backs of the last frame.
#include <epoxy/gl.h>

#include <algorithm>
#include <limits>
#include <map>
#include <memory>

#include "box_downsample.h"
#include "memory_plan.h"
#include "penumbra/channel_layout.h"
#include "penumbra/error.h"
#include "penumbra/gl/cascaded_reference.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/point_light.h"
#include "penumbra/shadow_lookup.h"
#include "penumbra/shared/cascade_selection.h"
#include "penumbra/shared/point_light_faces.h"
#include "penumbra/shared/shading.h"
#include "penumbra/shared/soft_shadow.h"
#include "penumbra/shared/summed_area.h"
#include "renderer_state.h"
#include "texture_readback.h"

namespace penumbra::gl {
namespace {

// One map fitted to the scene, as a single cascade whose box is its whole uv square.
CascadeFrame singleMap(const LightView& view) {
  CascadeFrame one;
  one.light = view;
  one.count = 1;
  one.start = 0.0f;
  one.ends.fill(std::numeric_limits<float>::max());
  one.boxes[0] = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  one.blendBand = 0.0f;
  return one;
}

// What the filter takes of the renderer's settings (the rest shapes the frame, not the map).
FilterSettings filterSettingsFor(const RenderSettings& s) {
  FilterSettings f;
  f.technique = s.technique;
  f.params = s.params;
  f.blur = s.blur;
  f.filter = s.filter;
  f.anisotropy = s.anisotropy;
  f.fusePrefilter = s.fusePrefilter;
  return f;
}

// ESM with a classifier reports its failure rate, counted on the diagnostic image: in a frame
// that reads the diagnostic back, so that one that reads nothing has nothing to wait for.
bool reportsFailureRate(const RenderSettings& s) {
  return s.technique == Technique::Esm && s.params.esm.classifier != shaders::kEsmClassifyNone &&
         (s.readBack & frame_image::kDiagnostic) != 0;
}

double failureRatePercent(const Image& diagnostic) {
  size_t drawn = 0, failed = 0;
  for (float v : diagnostic.data()) {
    drawn += v >= 0.0f;
    failed += v > 0.5f;
  }
  return drawn == 0 ? 0.0 : 100.0 * double(failed) / double(drawn);
}

// The splits of a frame that did not read Lloyd's back: every interior split NaN, so that no one
// takes them for the ones used.
shaders::LayerSplits unreadLayerSplits(int layerCount) {
  shaders::LayerSplits splits = shaders::uniformLayerSplits(layerCount);
  for (glm::vec4& row : splits.interior) row = glm::vec4(std::numeric_limits<float>::quiet_NaN());
  return splits;
}

}  // namespace

// Box-averages factor x factor blocks.
Image boxDownsample(const Image& image, int factor) {
  if (factor == 1) return image;
  Image out(image.width() / factor, image.height() / factor, image.channels());
  const float weight = 1.0f / float(factor * factor);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      for (int c = 0; c < image.channels(); ++c) {
        float sum = 0.0f;
        for (int j = 0; j < factor; ++j) {
          for (int i = 0; i < factor; ++i) sum += image.at(x * factor + i, y * factor + j, c);
        }
        out.at(x, y, c) = sum * weight;
      }
    }
  }
  return out;
}

LookupPixel lookupPixelInNextCascade(const LookupPixel& pixel, const CascadeFrame& cascades,
                                     int cascade, int size) {
  const glm::vec4 box = cascades.boxes[size_t(cascade)];
  const glm::vec4 next = cascades.boxes[size_t(cascade + 1)];
  const glm::vec2 extent(box.z, box.w);
  LookupPixel other = pixel;
  other.uv = shaders::cascadeUv(pixel.uv * extent + glm::vec2(box.x, box.y), next, 0);
  other.uvDx = shaders::cascadeUv(pixel.uvDx * extent, next, 1);
  other.uvDy = shaders::cascadeUv(pixel.uvDy * extent, next, 1);
  other.depthPerTexel =
      shaders::cascadeDepthPerTexel(pixel.depthPerTexel * float(size) / extent, next, size);
  return other;
}

LookupPixel lookupPixelAt(const RenderResult& r, int x, int y) {
  if (r.lookup.channels() != 4) {
    throw Error("the frame has no lookup inputs: render it with RenderSettings::lookupInputs");
  }
  LookupPixel p;
  p.uv = {r.lookup.at(x, y, 0), r.lookup.at(x, y, 1)};
  p.receiverDepth = r.lookup.at(x, y, 2);
  p.uvDx = {r.uvDerivatives.at(x, y, 0), r.uvDerivatives.at(x, y, 1)};
  p.uvDy = {r.uvDerivatives.at(x, y, 2), r.uvDerivatives.at(x, y, 3)};
  p.depthPerTexel = {r.receiverPlane.at(x, y, 0), r.receiverPlane.at(x, y, 1)};
  return p;
}

void Renderer::setScene(const Scene& scene) {
  State& s = *state_;
  const uint64_t layout = sceneLayoutFingerprint(scene);
  const uint64_t fingerprint = sceneFingerprint(scene, layout);
  if (s.scene && fingerprint == s.sceneFingerprint) {
    s.sceneDefaults.name = scene.name;
    s.sceneDefaults.camera = scene.camera;
    s.sceneDefaults.light = scene.light;
    return;
  }
  s.techniqueFrame = false;  // the last frame's geometry is gone
  if (scene.meshes.empty() || scene.triangleCount() == 0) {
    throw Error("scene '" + scene.name + "' has no triangles to draw");
  }
  if (s.scene && layout == s.sceneLayoutFingerprint) {
    s.scene->updateVertices(scene);  // a new pose of the same scene
  } else {
    s.scene = std::make_unique<GpuScene>(scene);
    s.depthBounds.forget();  // another scene's bounds (a new pose's are a frame late as ever)
  }
  s.sceneFingerprint = fingerprint;
  s.sceneLayoutFingerprint = layout;
  s.viewBounds = scene.viewBounds();
  s.sceneDefaults = Scene{};
  s.sceneDefaults.name = scene.name;
  s.sceneDefaults.camera = scene.camera;
  s.sceneDefaults.light = scene.light;
}

RenderResult Renderer::render(const Scene& scene, const RenderSettings& settings) {
  setScene(scene);
  return render(settings, FrameView{scene.camera, scene.light});
}

void Renderer::checkSoftShadows(const RenderSettings& settings, const Light& light) {
  checkLightSize(light);
  if (light.size == 0.0f) return;
  if (settings.cascades.count > 1) {
    throw Error("soft shadows (light size " + std::to_string(light.size) +
                ") are not supported with cascades: use one map (--cascades 1)");
  }
  if (prefiltersChannels(settings.technique) &&
      (settings.filter == FilterMode::Point || settings.filter == FilterMode::Bilinear)) {
    throw Error(std::string("soft shadows for ") + std::string(techniqueId(settings.technique)) +
                " widen the filter by mip level or summed-area box: use --filter trilinear, "
                "anisotropic or sat, not " +
                std::string(filterModeName(settings.filter)));
  }
}

RenderResult Renderer::render(const RenderSettings& settings, const FrameView& view) {
  requireCascadableLight(settings.cascades, view.light);
  validate(settings, view.light.kind);
  checkSoftShadows(settings, view.light);
  RenderResult result = renderFrame(settings, view, false);
  state_->techniqueFrame = true;
  if (reportsFailureRate(settings)) {
    result.failureRatePercent = failureRatePercent(result.diagnostic);
  }
  return result;
}

RenderResult Renderer::renderReference(const Scene& scene, const RenderSettings& settings,
                                       int supersample) {
  setScene(scene);
  return renderReference(settings, FrameView{scene.camera, scene.light}, supersample);
}

RenderResult Renderer::renderReference(const RenderSettings& settings, const FrameView& view,
                                       int supersample) {
  checkRange("reference supersampling", supersample, 1, 8);
  RenderSettings big = settings;
  big.msaaSamples = 1;
  big.lookupInputs = true;  // the CPU completes the pixels the GPU leaves from them
  big.width = settings.width * supersample;
  big.height = settings.height * supersample;
  requireCascadableLight(settings.cascades, view.light);
  validate(big, view.light.kind);
  // Supersampled, only the averaged colour, visibility and diagnostic are returned, as the
  // caller asks (the visibility always: it marks the pixels left to the CPU); the lookup's
  // inputs are read back only when the CPU has pixels to complete (completeReferenceOnCpu).
  namespace fi = frame_image;
  if (supersample > 1) {
    big.readBack = (settings.readBack & (fi::kColor | fi::kDiagnostic)) | fi::kVisibility;
  }
  RenderResult full = renderFrame(big, view, true);
  completeReferenceOnCpu(full);
  if (supersample == 1) return full;
  auto averaged = [&](const Image& image, unsigned bit) {
    return settings.readBack & bit ? boxDownsample(image, supersample) : Image{};
  };
  RenderResult result;
  result.color = averaged(full.color, fi::kColor);
  result.visibility = boxDownsample(full.visibility, supersample);
  result.diagnostic = averaged(full.diagnostic, fi::kDiagnostic);
  result.params = full.params;
  result.cascadeFrame = full.cascadeFrame;
  result.cascadeBlurs = full.cascadeBlurs;
  result.depthBounds = full.depthBounds;
  result.wallTimes = full.wallTimes;
  result.gpuTimes = full.gpuTimes;
  result.memory = full.memory;
  result.fusedPrefilter = full.fusedPrefilter;
  return result;
}

RenderResult Renderer::renderFrame(const RenderSettings& settings, const FrameView& view,
                                   bool reference) {
  State& s = *state_;
  if (!s.scene) throw Error("no scene to render: call Renderer::setScene first");
  s.settings = settings;
  s.techniqueFrame = false;  // Renderer::render sets it once the frame is done
  s.programs.setTechnique(settings.technique);
  for (GpuTimer* timer : {&s.light.timer, &s.camera.timer, &s.depthBoundsTimer}) {
    timer->setEnabled(settings.timing);
  }
  s.shadows.setTiming(settings.timing);

  // Where the frame is seen from, and the cascades that cover it.
  FrameGeometry& frame = s.frame;
  frame.camera = view.camera;
  frame.shadowCamera = view.shadowCamera.value_or(view.camera);
  frame.light = view.light;
  frame.viewBounds = s.viewBounds;
  frame.shadowMapSize = settings.shadowMapSize;
  frame.lightView = fitLightView(view.light, s.viewBounds.shadowed);
  const float aspect = float(settings.width) / float(settings.height);
  // What the frame reads back. A reference frame's visibility marks the pixels the CPU completes
  // (completeReferenceOnCpu reads the colour and diagnostic it shades them from where they were
  // not asked for). The lookup's inputs are read only where the frame writes them. A frame that
  // reads nothing and is not timed waits for nothing where the GPU keeps pace: it takes the
  // previous frame's depth bounds (DepthBoundsPass::measure) and leaves LVSM's Lloyd splits on
  // the GPU.
  namespace fi = frame_image;
  const bool lookupInputs = reference || settings.lookupInputs;
  const unsigned lookupImages =
      fi::kLookup | fi::kReceiverPlane | fi::kUvDerivatives | fi::kCascades;
  const unsigned reads = (settings.readBack | (reference ? fi::kVisibility : fi::kNone)) &
                         (lookupInputs ? fi::kAll : fi::kAll & ~lookupImages);
  const bool waits = reads != fi::kNone || settings.timing;
  DepthRange range{cameraNear(s.viewBounds), cameraFar(frame.shadowCamera, s.viewBounds)};
  s.depthBoundsTimer.reset();
  if (fitsDepthBounds(settings)) {
    s.depthBoundsTimer.begin();
    const glm::mat4 clipFromWorld =
        clipFromView(frame.shadowCamera, aspect, s.viewBounds) * viewFromWorld(frame.shadowCamera);
    range = s.depthBounds.measure(s.programs, *s.scene, clipFromWorld, range, settings.width,
                                  settings.height, waits);
    s.depthBoundsTimer.end();
  } else {
    s.depthBounds.release();
  }
  frame.cascaded = settings.cascades.count > 1;
  frame.pointLight = view.light.kind == LightKind::Point;
  PointLightFaces faces;
  if (frame.pointLight) {
    // The guard band covers the prefilter's blur and the lookup's kernel at a face's edge. The
    // lookup's reach is taken as the blur's (PCF matched to the prefilter, the reference's own
    // kernel) for every technique, so that every render of a comparison sees the same faces;
    // PCF with a wider kernel of its own widens it.
    const int pcfReach =
        !reference && settings.technique == Technique::Pcf ? settings.params.pcf.radius + 1 : 0;
    const int lookupReach = std::max(settings.blur.radius + 1, pcfReach);
    // A light with a size: the soft lookups' blocker search and widened filters reach up to
    // their widest width beyond the edge (shared/point_light_faces.h).
    const int softWidth = !reference && view.light.size > 0.0f
                              ? int(shaders::pointLightSoftWidthTexels(settings.shadowMapSize))
                              : 0;
    faces = pointLightFaces(
        frame.lightView, view.light.position, settings.shadowMapSize,
        shaders::pointFaceGuardTexels(settings.blur.radius, lookupReach, softWidth));
    frame.lightView.clipFromLight = faces.clipFromLight;
    frame.pointFaceTangent = faces.tangent;
  }
  frame.cascades = frame.pointLight ? pointLightCascadeFrame(frame.lightView)
                   : frame.cascaded
                       ? fitCascades(settings.cascades, frame.shadowCamera, aspect, range,
                                     view.light, s.viewBounds.shadowed, settings.shadowMapSize)
                       : singleMap(frame.lightView);
  const int count = frame.cascades.count;
  s.cascadeBlurs.assign(1, settings.blur);
  for (int c = 1; c < count; ++c) {
    s.cascadeBlurs.push_back(
        cascadeBlur(settings.blur, frame.cascades.kernelScale(c, settings.shadowMapSize)));
  }

  // Light pass: one layer per cascade.
  s.light.prepare({settings.shadowMapSize, reference ? 1 : settings.msaaSamples, count});
  std::vector<LightLayerView> layers;
  for (int c = 0; c < count; ++c) {
    LightLayerView layer;
    layer.lightFromWorld =
        frame.pointLight ? faces.lightFromWorld[size_t(c)] : frame.lightView.lightFromWorld;
    layer.clipFromLight =
        frame.cascaded ? frame.cascades.clipFromLight(c) : frame.lightView.clipFromLight;
    layer.nearDistance = frame.lightView.nearDistance;
    layer.farDistance = frame.lightView.farDistance;
    layer.perspective = frame.lightView.perspective;
    layers.push_back(layer);
  }
  // Translucent casters: dithered for the references and the techniques that average the
  // dither to 1 - alpha, a mask at 0.5 for the others (docs/techniques.md).
  s.light.render(s.programs, *s.scene, layers,
                 reference || carriesTranslucency(settings.technique));

  // The filter: the renderer is a host of the public filtering API like any other.
  FilterSettings filterSettings = filterSettingsFor(settings);
  if (frame.cascaded) {
    filterSettings.layerBlurs = s.cascadeBlurs;
    for (int c = 0; c < count; ++c) {
      filterSettings.layerKernelScales.push_back(
          frame.cascades.kernelScale(c, settings.shadowMapSize));
    }
  }
  DepthInput depth;
  depth.texture = s.light.depthTexture();
  depth.size = settings.shadowMapSize;
  depth.layers = count;
  depth.samples = s.light.shape().samples;
  depth.encoding = DepthEncoding::LinearDepth;
  if (reference) {
    s.shadows.prepareRawDepth(depth, filterSettings);
  } else {
    s.shadows.filter(depth, filterSettings);
  }
  const bool fused = s.shadows.state().fused;

  s.camera.prepare(settings.width, settings.height, writesDiagnostics(settings), lookupInputs);
  s.camera.render(s.programs, *s.scene, settings, frame, s.shadows, reference);

  RenderResult result;
  if (reads & fi::kColor) result.color = s.camera.readColor();
  if (reads & fi::kVisibility) result.visibility = s.camera.readVisibility();
  if (reads & fi::kDiagnostic) result.diagnostic = s.camera.readDiagnostic();
  if (reads & fi::kLookup) result.lookup = s.camera.readLookup();
  if (reads & fi::kReceiverPlane) result.receiverPlane = s.camera.readReceiverPlane();
  if (reads & fi::kUvDerivatives) result.uvDerivatives = s.camera.readUvDerivatives();
  if (reads & fi::kCascades) result.cascades = s.camera.readCascades();
  result.cascadeFrame = frame.cascades;
  result.cascadeBlurs = s.cascadeBlurs;
  result.depthBounds = range;
  // LVSM's Lloyd splits stay on the GPU in a frame that waits for nothing (ShadowFilter::params
  // reads them back); one that reads an image or its times waits anyway.
  if (waits || !s.shadows.state().splitsOnGpu) {
    result.params = s.shadows.params();
  } else {
    result.params = s.shadows.state().params;
    result.params.lvsm.splits = unreadLayerSplits(result.params.lvsm.splits.layerCount);
  }
  result.fusedPrefilter = fused;
  auto times = [&](auto read) {
    PassTimes t;
    t.light = read(s.light.timer);
    t.camera = read(s.camera.timer);
    t.depthBounds = read(s.depthBoundsTimer);
    if (!reference) {
      const ShadowFilter::State& f = s.shadows.state();
      t.encode = read(f.maps.encodeTimer);
      t.prefilter = read(f.maps.prefilterTimer);
      t.mipsOrSat = read(f.maps.mipsTimer);
      t.auxiliary = read(f.auxiliaryTimer);
    }
    return t;
  };
  // A software rasteriser's queries see only submission, and llvmpipe's lose their start
  // around draws that change framebuffers (the mip pass read its uptime): no GPU times there.
  if (settings.timing && timerQueriesMeasureExecution()) {
    result.gpuTimes = times([](const GpuTimer& t) { return t.gpuMilliseconds(); });
  }
  if (settings.timing) {
    result.wallTimes = times([](const GpuTimer& t) { return t.wallMilliseconds(); });
  }
  result.memory = s.memory();
  return result;
}

// Pixels whose reference kernel needs more texel tests than one shader invocation may run are
// marked -1 by the camera pass (with the albedo in colour and the light amount in the
// diagnostic); the CPU twin of their cascade evaluates them with the same shared code, the next
// cascade's lookup re-expressed through the cascades' boxes in the blend band.
void Renderer::completeReferenceOnCpu(RenderResult& r) const {
  const State& s = *state_;
  const RenderSettings& settings = s.settings;
  const auto& marked = r.visibility.data();
  if (std::none_of(marked.begin(), marked.end(), [](float v) { return v < 0.0f; })) return;
  // The lookup's inputs of the frame just drawn, where the frame did not read them back.
  if (r.lookup.empty()) r.lookup = s.camera.readLookup();
  if (r.receiverPlane.empty()) r.receiverPlane = s.camera.readReceiverPlane();
  if (r.uvDerivatives.empty()) r.uvDerivatives = s.camera.readUvDerivatives();
  if (r.cascades.empty()) r.cascades = s.camera.readCascades();
  // The shading of the completed pixels needs their albedo and light amount.
  if (r.color.empty()) r.color = s.camera.readColor();
  if (r.diagnostic.empty()) r.diagnostic = s.camera.readDiagnostic();
  CascadedReference reference(r, settings.shadowMapSize, settings.filter, settings.anisotropy,
                              s.limits.halfRounding,
                              [this](int cascade) { return readDepthMap(cascade); });
  for (int y = 0; y < r.visibility.height(); ++y) {
    for (int x = 0; x < r.visibility.width(); ++x) {
      if (r.visibility.at(x, y) >= 0.0f) continue;
      const float v = reference.visibilityAt(x, y);
      const glm::vec3 albedo(r.color.at(x, y, 0), r.color.at(x, y, 1), r.color.at(x, y, 2));
      const glm::vec3 shaded =
          shaders::shadeLambert(albedo, settings.ambient, r.diagnostic.at(x, y), v);
      for (int c = 0; c < 3; ++c) r.color.at(x, y, c) = shaded[c];
      r.visibility.at(x, y) = v;
      r.diagnostic.at(x, y) = 0.0f;
    }
  }
}

void Renderer::filterDepthMap(const Image& depth, const RenderSettings& settings) {
  RenderSettings single = settings;
  single.msaaSamples = 1;
  single.shadowMapSize = depth.width();
  single.cascades = CascadeSettings{};
  if (depth.width() != depth.height() || depth.channels() != 1) {
    throw Error("filterDepthMap needs a square one-channel depth map");
  }
  validate(single);
  State& s = *state_;
  s.settings = single;
  s.techniqueFrame = false;
  s.uploadedDepth.emplace(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(s.uploadedDepth->id(), 1, GL_R32F, depth.width(), depth.height(), 1);
  glTextureSubImage3D(s.uploadedDepth->id(), 0, 0, 0, 0, depth.width(), depth.height(), 1, GL_RED,
                      GL_FLOAT, depth.data().data());
  FilterSettings filterSettings = filterSettingsFor(single);
  // The parity path filters with the splits given: Lloyd's placement is the frames' to test.
  if (filterSettings.params.lvsm.placement == shaders::kLayerPlacementLloyd) {
    filterSettings.params.lvsm.placement = shaders::kLayerPlacementFixed;
  }
  DepthInput input;
  input.texture = s.uploadedDepth->id();
  input.size = depth.width();
  input.encoding = DepthEncoding::LinearDepth;
  s.shadows.filter(input, filterSettings);
}

Image Renderer::readDepthMap(int cascade) const {
  return state_->light.readDepth(cascade);
}

Image Renderer::readCameraDepth() const {
  return state_->camera.readDepth();
}

Image Renderer::readDepthSamples(int cascade) const {
  return state_->light.readDepthSamples(state_->programs, cascade);
}

int Renderer::channelMipLevels() const {
  return state_->shadows.channelMipLevels();
}

double Renderer::timeMinimalLookup(bool esmFallback) {
  State& s = *state_;
  if (!s.scene || s.camera.bytes() == 0) {
    throw Error("no frame to draw the minimal lookup of: call Renderer::render first");
  }
  if (!prefiltersChannels(s.settings.technique)) {
    throw Error(std::string(techniqueId(s.settings.technique)) +
                " has no minimal lookup: it filters after the test, over the light pass's depth");
  }
  const ChannelLayout layout = channelLayout(s.settings.technique, s.shadows.params());
  s.camera.renderMinimalLookup(s.programs, *s.scene, s.settings, s.frame, s.shadows, layout.layers,
                               esmFallback);
  return s.camera.minimalTimer.milliseconds(timerQueriesMeasureExecution());
}

double Renderer::timeCameraPass() {
  State& s = *state_;
  if (!s.scene || s.camera.bytes() == 0 || !s.techniqueFrame) {
    throw Error(
        "no technique's frame to draw the camera pass of again: call Renderer::render "
        "first");
  }
  const bool timing = s.settings.timing;
  s.camera.timer.setEnabled(true);
  s.camera.timer.reset();  // the frame's own time is not this draw's
  s.camera.render(s.programs, *s.scene, s.settings, s.frame, s.shadows, false);
  const double ms = s.camera.timer.milliseconds(timerQueriesMeasureExecution());
  s.camera.timer.setEnabled(timing);
  return ms;
}

double Renderer::timeEncodePass() {
  ShadowFilter::State& f = state_->shadows.state();
  if (!f.filtered || f.fused) {
    throw Error(
        "no separate encode pass to dispatch again: call Renderer::render or filterDepthMap "
        "first, without fusePrefilter");
  }
  return f.maps.timeEncode(f.programs, f.parameters, f.depth.texture, f.depth.samples,
                           timerQueriesMeasureExecution());
}

Image Renderer::readCameraColor() const {
  return state_->camera.readColor();
}

Image Renderer::readMinimalLookupColor() const {
  return state_->camera.readMinimalLookupColor();
}

int Renderer::minimalLookupDraws(bool esmFallback) const {
  return state_->camera.minimalLookupDraws(esmFallback);
}

uint64_t Renderer::measuredChannelTextureBytes() const {
  const State& s = *state_;
  uint64_t bytes = 0;
  if (s.shadows.state().maps.channels().id() == 0) return 0;  // PCF, the hard test: none
  for (int level = 0; level < s.shadows.state().maps.shape().levels; ++level) {
    GLint width = 0, height = 0, depth = 0, bits = 0;
    const GLuint t = s.shadows.state().maps.channels().id();
    glGetTextureLevelParameteriv(t, level, GL_TEXTURE_WIDTH, &width);
    glGetTextureLevelParameteriv(t, level, GL_TEXTURE_HEIGHT, &height);
    glGetTextureLevelParameteriv(t, level, GL_TEXTURE_DEPTH, &depth);
    for (GLenum component : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE,
                             GL_TEXTURE_ALPHA_SIZE}) {
      GLint size = 0;
      glGetTextureLevelParameteriv(t, level, component, &size);
      bits += size;
    }
    bytes += uint64_t(width) * uint64_t(height) * uint64_t(depth) * uint64_t(bits / 8);
  }
  checkErrors("measuring the channel texture");
  return bytes;
}

uint64_t Renderer::measuredFrameBytes() const {
  return state_->camera.measuredBytes();
}

namespace {

// PCF's and the hard test's one channel, which no texture holds: a cascade's light-pass depth as
// their lookup reads it (passes/light_depth_texels.comp).
Image readLightDepthTexels(ProgramCache& programs, const ShadowFilter& shadows, int size,
                           int cascade) {
  const Program& program = programs.compute("passes/light_depth_texels.comp",
                                            lookupVariantDefines(shadows.state(), false));
  Texture target(GL_TEXTURE_2D);
  glTextureStorage2D(target.id(), 1, GL_R32F, size, size);
  shadows.bind();
  program.set("cascade", cascade);
  glBindImageTexture(0, target.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  program.dispatch((unsigned(size) + 7u) / 8u, (unsigned(size) + 7u) / 8u);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  return readTexture(target.id(), 0, size, size, 1, 1, GL_RED, false);
}

}  // namespace

Image Renderer::readChannels(int level, int cascade) const {
  const State& s = *state_;
  const ChannelShape& shape = s.shadows.state().maps.shape();
  checkRange("mip level", level, 0, shape.levels - 1);
  checkRange("cascade", cascade, 0, shape.cascades - 1);
  if (!shape.texture) return readLightDepthTexels(state_->programs, s.shadows, shape.size, cascade);
  const int size = std::max(1, shape.size >> level);
  const ChannelLayout& layout = shape.layout;
  const GLenum formats[5] = {0, GL_RED, GL_RG, GL_RGBA, GL_RGBA};
  // Every cascade's layers come back, cascade by cascade; channel c of a cascade is component
  // c of its layers (4 per layer when there are several).
  Image all = readTexture(s.shadows.state().maps.channels().id(), level, size, size,
                          layout.layers * shape.cascades, layout.componentsPerTexel,
                          formats[layout.componentsPerTexel], false);
  Image trimmed(size, size, layout.channels);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      for (int c = 0; c < layout.channels; ++c) {
        trimmed.at(x, y, c) = all.at(x, y, cascade * layout.layers * layout.componentsPerTexel + c);
      }
    }
  }
  return trimmed;
}

Image Renderer::readZmaxLevel(int level) const {
  const State& s = *state_;
  const ZmaxPyramid& zmax = s.shadows.state().zmax;
  if (!zmax.built()) throw Error("no Z-max pyramid: render ESM with classifier=zmax first");
  checkRange("Z-max level", level, 0, zmax.levels() - 1);
  const int size = std::max(1, s.light.shape().size >> level);
  Image all = readTexture(zmax.texture().id(), level, size, size, s.light.shape().cascades, 1,
                          GL_RED, false);
  Image first(size, size, 1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) first.at(x, y) = all.at(x, y, 0);
  }
  return first;
}

std::vector<SplitSample> Renderer::readSplitSamples() const {
  if (!state_->shadows.state().lloyd.placed())
    throw Error("no Lloyd samples: render LVSM with placement=lloyd first");
  return state_->shadows.state().lloyd.readSamples();
}

Renderer::SummedAreaChannelStats Renderer::summedAreaQuantisation(int channel) const {
  const State& s = *state_;
  if (!s.shadows.state().maps.hasSummedAreaTable()) {
    throw Error("no summed-area table: render with the 'sat' filter first");
  }
  const ChannelShape& shape = s.shadows.state().maps.shape();
  // The stats buffer holds SatChannelStats (lib/summed_area.glsl), {centre, step}, per channel.
  std::vector<SummedAreaChannelStats> stats(size_t(shape.layout.channels * shape.cascades));
  s.shadows.state().maps.summedAreaStats().read(std::as_writable_bytes(std::span(stats)));
  return stats.at(size_t(channel));
}

double Renderer::summedAreaBoxMean(int x0, int y0, int x1, int y1, int channel) const {
  const SummedAreaChannelStats q = summedAreaQuantisation(channel);
  const State& s = *state_;
  const int size = s.shadows.state().maps.shape().size;
  auto prefix = [&](int x, int y) -> uint64_t {
    if (x < 0 || y < 0) return 0;
    uint64_t v = 0;
    const size_t index = shaders::summedAreaIndex(channel, x, y, size, size);
    glGetNamedBufferSubData(s.shadows.state().maps.summedAreaSums().id(), GLintptr(index * 8), 8,
                            &v);
    return v;
  };
  const uint64_t wrapped =
      prefix(x1, y1) - prefix(x0 - 1, y1) - prefix(x1, y0 - 1) + prefix(x0 - 1, y0 - 1);
  const double area = double(x1 - x0 + 1) * double(y1 - y0 + 1);
  return shaders::summedAreaMean(double(int64_t(wrapped)), area, q.step, q.centre);
}

}  // namespace penumbra::gl
