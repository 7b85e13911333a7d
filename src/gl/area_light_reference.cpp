// The area-light reference (docs/reference.md): the mean of hard shadow tests from shadow maps
// rendered at stratified points of the light's disk (directional, spot) or sphere (point: each
// sample weighted by the solid angle it stands for from the pixel's receiver), the visibility an
// area light really gives (up to the stratification and the maps' resolution), against which soft
// shadows are measured.
#include <optional>
#include <vector>

#include "box_downsample.h"
#include "penumbra/area_light.h"
#include "penumbra/error.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/shared/light_depth.h"
#include "penumbra/shared/point_light_faces.h"
#include "penumbra/shared/shadow_lookup.h"
#include "renderer_state.h"

namespace penumbra::gl {
namespace {

// One point light's exact hard test: a one-texel PCF against the receiver plane (no acne on
// planar receivers) with only the reference's rounding tie as bias, nothing to prefilter.
RenderSettings hardTestSettings(const RenderSettings& settings, int supersample) {
  RenderSettings hard = settings;
  hard.technique = Technique::Pcf;
  hard.params.pcf.kernel = shaders::kKernelBox;
  hard.params.pcf.radius = 0;
  hard.params.pcf.receiverPlane = 1;
  hard.params.pcf.bias.constantBias = shaders::kReferenceTie;
  hard.params.pcf.bias.slopeScaledBias = 0.0f;
  hard.filter = FilterMode::Point;
  hard.blur = BlurSpec{BlurKernel::Box, 0, 1.0f};
  hard.msaaSamples = 1;
  hard.lookupInputs = true;  // each pixel's lookup finds its receiver on the light's faces
  hard.width = settings.width * supersample;
  hard.height = settings.height * supersample;
  return hard;
}

void accumulate(Image& sum, const Image& image) {
  for (size_t i = 0; i < sum.data().size(); ++i) sum.data()[i] += image.data()[i];
}

void scale(Image& image, float factor) {
  for (float& v : image.data()) v *= factor;
}

// Where each pixel's receiver lies, from a point light's frame (its face, uv and linear depth:
// pointFaceUv and pointLightDepth inverted); nullopt where the pixel is outside the map. The
// position is the lookup's, normal offset included (a fraction of a texel).
std::vector<std::optional<glm::vec3>> pointLightReceivers(const RenderResult& r,
                                                          glm::vec3 lightPosition) {
  const LightView& view = r.cascadeFrame.light;
  const float tangent = 1.0f / view.clipFromLight[0][0];  // the faces' (guard band included)
  std::vector<std::optional<glm::vec3>> receivers;
  receivers.reserve(size_t(r.lookup.width()) * size_t(r.lookup.height()));
  for (int y = 0; y < r.lookup.height(); ++y) {
    for (int x = 0; x < r.lookup.width(); ++x) {
      if (r.lookup.at(x, y, 3) <= 0.0f) {
        receivers.emplace_back();
        continue;
      }
      const int face = int(r.cascades.at(x, y, 0));
      const glm::vec2 uv(r.lookup.at(x, y, 0), r.lookup.at(x, y, 1));
      const float distance =
          shaders::lightDistanceAtDepth(r.lookup.at(x, y, 2), view.nearDistance, view.farDistance);
      receivers.emplace_back(lightPosition +
                             distance * shaders::pointFaceDirection(face, uv, tangent));
    }
  }
  return receivers;
}

// The centre frame a sphere light's receivers are found from: its lookup and cascades, whatever
// else the caller's settings read back.
RenderSettings receiverSettings(RenderSettings settings) {
  settings.readBack |= frame_image::kLookup | frame_image::kCascades;
  return settings;
}

}  // namespace

RenderResult Renderer::renderAreaLightReference(const RenderSettings& settings,
                                                const FrameView& view, int samples,
                                                int supersample) {
  checkRange("reference supersampling", supersample, 1, 8);
  checkAreaLightSamples(samples);
  checkLightSize(view.light);
  if (!(view.light.size > 0.0f)) {
    throw Error("the area-light reference needs a light with a size (--light-size)");
  }
  if (settings.cascades.count > 1) {
    throw Error("the area-light reference renders one map per light sample: use --cascades 1");
  }
  const RenderSettings hard = hardTestSettings(settings, supersample);
  validate(hard);
  FrameView centre = view;
  centre.light.size = 0.0f;
  const bool sphere = view.light.kind == LightKind::Point;
  std::vector<Light> lights;
  std::vector<glm::vec3> spherePoints;
  if (sphere) {
    spherePoints = stratifiedSphereSamples(samples);
    for (const glm::vec3 point : spherePoints)
      lights.push_back(sphereLightSample(view.light, point));
  } else {
    for (const glm::vec2 point : stratifiedDiskSamples(samples)) {
      lights.push_back(areaLightSample(view.light, point));
    }
  }
  // A sphere's samples count by the solid angle each covers from the pixel's receiver, found
  // from the centre's frame; pixels outside the map, or that see no sample (on the light), take
  // the plain mean.
  const std::vector<std::optional<glm::vec3>> receivers =
      sphere ? pointLightReceivers(renderFrame(receiverSettings(hard), centre, false),
                                   view.light.position)
             : std::vector<std::optional<glm::vec3>>{};
  Image visibility(hard.width, hard.height, 1);
  Image color(hard.width, hard.height, 4);
  Image weighted(hard.width, hard.height, 1);
  Image weightedColor(hard.width, hard.height, 4);
  Image weights(hard.width, hard.height, 1);
  std::optional<PassTimes> wall = PassTimes{};  // while every sample's frame is timed
  std::optional<PassTimes> gpu = PassTimes{};   // while every sample's frame has GPU times
  // A light sample's frame gives its colour and visibility only: the lookup's inputs are the
  // centre's (below), so the samples' frames neither write nor read them.
  RenderSettings sampleSettings = hard;
  sampleSettings.lookupInputs = false;
  sampleSettings.readBack = frame_image::kColor | frame_image::kVisibility;
  for (size_t i = 0; i < lights.size(); ++i) {
    FrameView sample = view;
    sample.light = lights[i];
    const RenderResult r = renderFrame(sampleSettings, sample, false);
    accumulate(visibility, r.visibility);
    accumulate(color, r.color);
    if (sphere) {
      for (int y = 0; y < hard.height; ++y) {
        for (int x = 0; x < hard.width; ++x) {
          const std::optional<glm::vec3>& at =
              receivers[size_t(y) * size_t(hard.width) + size_t(x)];
          const float w = at ? sphereLightSampleWeight(view.light, spherePoints[i], *at) : 0.0f;
          weights.at(x, y) += w;
          weighted.at(x, y) += w * r.visibility.at(x, y);
          for (int c = 0; c < 4; ++c) weightedColor.at(x, y, c) += w * r.color.at(x, y, c);
        }
      }
    }
    if (wall && r.wallTimes) {
      wall->light += r.wallTimes->light;
      wall->camera += r.wallTimes->camera;
    } else {
      wall.reset();
    }
    if (gpu && r.gpuTimes) {
      gpu->light += r.gpuTimes->light;
      gpu->camera += r.gpuTimes->camera;
    } else {
      gpu.reset();
    }
  }
  scale(visibility, 1.0f / float(samples));
  scale(color, 1.0f / float(samples));
  for (int y = 0; y < hard.height; ++y) {
    for (int x = 0; x < hard.width; ++x) {
      const float total = weights.at(x, y);
      if (!(total > 0.0f)) continue;
      visibility.at(x, y) = weighted.at(x, y) / total;
      for (int c = 0; c < 4; ++c) color.at(x, y, c) = weightedColor.at(x, y, c) / total;
    }
  }
  // The centre's lookup: coverage, receiver planes and the depth map the report reads. Its
  // colour, visibility and diagnostic give way to the samples' averages, and supersampled, its
  // per-pixel lookup inputs have no meaning at the frame's size: neither is read back.
  namespace fi = frame_image;
  RenderSettings centreSettings = hard;
  centreSettings.readBack = supersample > 1
                                ? fi::kNone
                                : hard.readBack & ~(fi::kColor | fi::kVisibility | fi::kDiagnostic);
  RenderResult result = renderFrame(centreSettings, centre, false);
  result.visibility = boxDownsample(visibility, supersample);
  result.color = boxDownsample(color, supersample);
  result.diagnostic = Image(result.visibility.width(), result.visibility.height(), 1);
  result.params = settings.params;
  result.wallTimes = wall;
  result.gpuTimes = gpu;
  return result;
}

}  // namespace penumbra::gl
