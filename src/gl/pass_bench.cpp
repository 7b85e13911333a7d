// The minimal kernels: a copy of the depth into every channel layer (beside encode), a plain
// separable blur of whole texels with the same taps (beside the prefilter) and the driver's own
// mipmap generation (beside the mip pass), on textures like the channel texture.
#include "penumbra/gl/pass_bench.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "channel_dispatch.h"
#include "gl_formats.h"
#include "gpu_timer.h"
#include "penumbra/error.h"
#include "penumbra/metrics.h"
#include "penumbra/filters.h"
#include "penumbra/gl/context.h"
#include "program_cache.h"

namespace penumbra::gl {
namespace {

Texture arrayTexture(unsigned format, int size, int layers, int levels) {
  Texture t(GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(t.id(), levels, format, size, size, layers);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER,
                      levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
  return t;
}

// Times `work` `repeats` times after one warm-up run; the median wall time.
template <typename Work>
double timeMedian(int repeats, Work work) {
  work();
  std::vector<double> times;
  GpuTimer timer;
  for (int i = 0; i < repeats; ++i) {
    timer.begin();
    work();
    timer.end();
    times.push_back(timer.wallMilliseconds());
  }
  return median(times);
}

}  // namespace

PassBenchResult benchPasses(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                            int repeats) {
  if (repeats < 1 || repeats > 100) {
    throw Error("bench repeats " + std::to_string(repeats) + " is out of range [1, 100]");
  }
  if (settings.technique == Technique::Pcf || settings.technique == Technique::Hard) {
    throw Error(std::string(techniqueId(settings.technique)) +
                " has no prefilter passes to measure (it filters after the test)");
  }
  if (settings.cascades.count != 1 || settings.filter == FilterMode::SummedArea) {
    throw Error("bench --passes measures one map with mips or none (no cascades, no sat)");
  }
  renderer.setScene(scene);
  std::vector<double> encode, prefilter, mips;
  renderer.render(scene, settings);  // warm-up: shader compilation, resources
  for (int i = 0; i < repeats; ++i) {
    const RenderResult r = renderer.render(scene, settings);
    encode.push_back(r.wallTimes.encode);
    prefilter.push_back(r.wallTimes.prefilter);
    mips.push_back(r.wallTimes.mipsOrSat);
  }

  const ChannelLayout layout = channelLayout(settings.technique, settings.params);
  const unsigned format = internalFormat(layout);
  const int size = settings.shadowMapSize;
  const int levels = renderer.channelMipLevels();
  ProgramCache programs;
  const std::vector<ShaderDefine> defines = formatDefines(layout);
  Texture depth = arrayTexture(GL_R32F, size, 1, 1);
  const float clearDepth = 0.5f;
  glClearTexImage(depth.id(), 0, GL_RED, GL_FLOAT, &clearDepth);
  Texture channels = arrayTexture(format, size, layout.layers, levels);
  Texture scratch = arrayTexture(format, size, layout.layers, 1);

  const Program& copy = programs.compute("passes/baseline_copy.comp", defines);
  setSize(copy, "size", size);
  copy.set("layerCount", layout.layers);
  const double copyMs = timeMedian(repeats, [&] {
    glBindTextureUnit(0, depth.id());
    bindChannelImage(channels, layout, 0);
    copy.dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
  });

  const Program& blur = programs.compute("passes/baseline_blur.comp", defines);
  const std::vector<float> weights = blurWeights(settings.blur);
  glProgramUniform1fv(blur.id(), glGetUniformLocation(blur.id(), "weights"),
                      GLsizei(weights.size()), weights.data());
  blur.set("radius", settings.blur.radius);
  blur.set("layerCount", layout.layers);
  setSize(blur, "size", size);
  const GLint direction = glGetUniformLocation(blur.id(), "direction");
  const double blurMs = timeMedian(repeats, [&] {
    glBindTextureUnit(0, channels.id());
    bindChannelImage(scratch, layout, 0);
    glProgramUniform2i(blur.id(), direction, 1, 0);
    blur.dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
    glBindTextureUnit(0, scratch.id());
    bindChannelImage(channels, layout, 0);
    glProgramUniform2i(blur.id(), direction, 0, 1);
    blur.dispatch(groups(size, kChannelGroup), groups(size, kChannelGroup));
  });

  PassBenchResult result;
  result.technique = settings.technique;
  result.format = imageFormatQualifier(layout) + " x " + std::to_string(layout.layers) +
                  (layout.layers == 1 ? " layer" : " layers");
  result.passes.push_back({"encode", median(encode), "copy depth to every layer", copyMs});
  result.passes.push_back({"prefilter", median(prefilter),
                           "plain separable blur, " + std::to_string(2 * settings.blur.radius + 1) +
                               " taps",
                           blurMs});
  if (levels > 1) {
    const double generateMs =
        timeMedian(repeats, [&] { glGenerateTextureMipmap(channels.id()); });
    result.passes.push_back({"mips", median(mips), "glGenerateTextureMipmap", generateMs});
  }
  checkErrors("bench --passes");
  return result;
}

}  // namespace penumbra::gl
