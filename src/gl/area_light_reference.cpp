// The area-light reference (docs/reference.md): the mean of hard shadow tests from shadow maps
// rendered at stratified points of the light's disk, the visibility an area light really gives
// (up to the stratification and the maps' resolution), against which soft shadows are measured.
#include "box_downsample.h"
#include "penumbra/area_light.h"
#include "penumbra/error.h"
#include "penumbra/gl/renderer.h"
#include "renderer_state.h"
#include "shared/shadow_lookup.h"

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
  Image visibility(hard.width, hard.height, 1);
  Image color(hard.width, hard.height, 4);
  PassTimes wall, gpu;
  for (const glm::vec2 point : stratifiedDiskSamples(samples)) {
    FrameView sample = view;
    sample.light = areaLightSample(view.light, point);
    const RenderResult r = renderFrame(hard, sample, false);
    accumulate(visibility, r.visibility);
    accumulate(color, r.color);
    wall.light += r.wallTimes.light;
    wall.camera += r.wallTimes.camera;
    gpu.light += r.gpuTimes.light;
    gpu.camera += r.gpuTimes.camera;
  }
  scale(visibility, 1.0f / float(samples));
  scale(color, 1.0f / float(samples));
  // The centre's lookup: coverage, receiver planes and the depth map the report reads.
  FrameView centre = view;
  centre.light.size = 0.0f;
  RenderResult result = renderFrame(hard, centre, false);
  result.visibility = boxDownsample(visibility, supersample);
  result.color = boxDownsample(color, supersample);
  result.diagnostic = Image(result.visibility.width(), result.visibility.height(), 1);
  if (supersample > 1) {
    // Per-pixel lookup inputs have no meaning at the frame's size once averaged.
    result.lookup = Image();
    result.receiverPlane = Image();
    result.uvDerivatives = Image();
    result.cascades = Image();
  }
  result.params = settings.params;
  result.wallTimes = wall;
  result.gpuTimes = gpu;
  return result;
}

}  // namespace penumbra::gl
