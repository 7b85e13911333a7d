// The renderer: construction, settings validation and the memory budget.
#include "penumbra/gl/renderer.h"

#include <epoxy/gl.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <iomanip>
#include <sstream>

#include "gl_formats.h"
#include "memory_plan.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/render_setting_values.h"
#include "penumbra/params.h"
#include "renderer_state.h"
#include "penumbra/shared/cascade_selection.h"
#include "penumbra/shared/filter_weights.h"

namespace penumbra::gl {
namespace {

std::string formatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

// Settings hold floats: compared in float, a documented bound (0.01 is 0.00999999978f) is itself
// accepted and one float step beyond it is not.
void checkRange(std::string_view what, float value, float lo, float hi) {
  if (!(value >= lo && value <= hi)) {
    throw Error(std::string(what) + " " + formatNumber(value) + " is out of range [" +
                formatNumber(lo) + ", " + formatNumber(hi) + "]");
  }
}

void checkRange(std::string_view what, int value, int lo, int hi) {
  if (value < lo || value > hi) {
    throw Error(std::string(what) + " " + std::to_string(value) + " is out of range [" +
                std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
}

namespace {

// 1 + 3/4 of an fp16 step at 1: rounding to nearest stores 1 + 2^-10, truncation stores 1.
HalfRounding probeHalfRounding(Renderer::State& s) {
  const float value = 1.0f + 3.0f / 4096.0f;
  Texture target(GL_TEXTURE_2D);
  glTextureStorage2D(target.id(), 1, GL_RGBA16F, 1, 1);
  const Program& probe = s.programs.compute("passes/half_rounding_probe.comp", {});
  probe.set("value", value);
  glBindImageTexture(0, target.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  probe.dispatch(1);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  float stored[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glGetTextureImage(target.id(), 0, GL_RGBA, GL_FLOAT, sizeof stored, stored);
  checkErrors("probing fp16 rounding");
  return stored[0] < value ? HalfRounding::TowardZero : HalfRounding::Nearest;
}

std::string gib(uint64_t bytes) {
  std::ostringstream out;
  out << std::setprecision(3) << double(bytes) / double(uint64_t(1) << 30) << " GiB";
  return out.str();
}

// What the GL can give one render, and where that figure comes from.
struct MemoryBudget {
  uint64_t bytes = 0;
  std::string source;
};

MemoryBudget glMemoryBudget(const Renderer::State& s) {
  // The vendor queries report free memory, which excludes what this renderer holds now and
  // frees or reuses for the next render.
  const uint64_t held = s.memory().total();
  if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
    GLint kib = 0;
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &kib);
    const uint64_t free = uint64_t(kib) * 1024 + held;
    return {free, "the " + gib(free) + " of GPU memory free (GL_NVX_gpu_memory_info)"};
  }
  if (epoxy_has_gl_extension("GL_ATI_meminfo")) {
    GLint kib[4] = {};
    glGetIntegerv(GL_TEXTURE_FREE_MEMORY_ATI, kib);
    const uint64_t free = uint64_t(kib[0]) * 1024 + held;
    return {free, "the " + gib(free) + " of texture memory free (GL_ATI_meminfo)"};
  }
  // llvmpipe and GLs that do not say: textures live in RAM beside the read-backs and reports.
  const uint64_t ram = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  return {ram / 2, "the budget of " + gib(ram / 2) + ", half of this machine's " + gib(ram) +
                       " of RAM (this GL does not report its memory)"};
}

MemoryBudget memoryBudget(const Renderer::State& s) {
  const MemoryBudget offered = glMemoryBudget(s);
  if (s.memoryLimit == 0 || s.memoryLimit >= offered.bytes) return offered;
  return {s.memoryLimit, "the limit of " + gib(s.memoryLimit) + " (" +
                             std::to_string(s.memoryLimit) + " bytes) set on the renderer"};
}

// The GL's own answer to "could this texture be created?" (proxy targets, GL 4.5 §8.22).
bool proxyAccepts(const PlannedTexture& t) {
  if (t.proxyTarget == GL_PROXY_TEXTURE_2D_MULTISAMPLE_ARRAY) {
    // Mesa takes multisample proxies only through TexImage (TexStorage wants a bound object).
    glTexImage3DMultisample(t.proxyTarget, t.samples, t.internalFormat, t.width, t.height, t.layers,
                            GL_TRUE);
  } else if (t.proxyTarget == GL_PROXY_TEXTURE_2D_ARRAY) {
    glTexStorage3D(t.proxyTarget, t.levels, t.internalFormat, t.width, t.height, t.layers);
  } else {
    glTexStorage2D(t.proxyTarget, t.levels, t.internalFormat, t.width, t.height);
  }
  GLint width = 0;
  glGetTexLevelParameteriv(t.proxyTarget, 0, GL_TEXTURE_WIDTH, &width);
  return width != 0;
}

// Why these settings do not fit beside the uploaded scene's `sceneBytes`, or nothing when they
// do.
std::string memoryShortfall(const RenderSettings& settings, const MemoryBudget& budget,
                            int maxArrayLayers, LightKind light, uint64_t sceneBytes) {
  for (const PlannedTexture& t : plannedTextures(settings, light)) {
    if (t.layers > maxArrayLayers) {
      return "its " + std::string(t.what) + " needs " + std::to_string(t.layers) +
             " array layers, more than this GL's " + std::to_string(maxArrayLayers);
    }
    if (!proxyAccepts(t)) {
      return "this GL cannot create its " + std::to_string(t.width) + "x" +
             std::to_string(t.height) + " " + std::string(t.what) + " of " + gib(t.bytes) +
             " (GL proxy test)";
    }
  }
  if (estimateMemory(settings, light).total() + sceneBytes > budget.bytes)
    return "that is more than " + budget.source;
  return {};
}

}  // namespace

MemoryReport Renderer::State::memory() const {
  MemoryReport m;
  m.lightPass = light.bytes();
  const FilterMemory f = shadows.memory();
  m.technique = f.channels;
  m.summedArea = f.summedArea;
  m.scratch = f.scratch;
  m.auxiliary = f.auxiliary;
  m.frame = camera.bytes() + depthBounds.bytes();
  m.geometry = scene ? scene->bytes() : 0;
  return m;
}

Renderer::Renderer(const Context& context) : state_(std::make_unique<State>()) {
  DeviceLimits& limits = state_->limits;
  limits.device = context.description();
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limits.maxTextureSize);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &limits.maxArrayLayers);
  limits.halfRounding = probeHalfRounding(*state_);
  checkErrors("creating the renderer");
}

HalfRounding Renderer::halfFloatRounding() const {
  return state_->limits.halfRounding;
}

Renderer::~Renderer() = default;

void Renderer::limitMemory(uint64_t bytes) {
  state_->memoryLimit = bytes;
}

std::string Renderer::deviceDescription() const {
  return state_->limits.device;
}

bool Renderer::timerQueriesMeasureExecution() const {
  const std::string& device = state_->limits.device;
  for (const char* software : {"llvmpipe", "softpipe", "SWR"}) {
    if (device.find(software) != std::string::npos) return false;
  }
  return true;
}

void Renderer::validate(const RenderSettings& settings, LightKind light) const {
  const DeviceLimits& s = state_->limits;
  // The shadow map's settings are the filter's to check (one place for the renderer and hosts);
  // the frame and the memory budget are the renderer's.
  state_->shadows.state().checkFilter(settings, shadowMapLayers(settings, light));
  checkRange("frame width", settings.width, kMinFrameSize, s.maxTextureSize);
  checkRange("frame height", settings.height, kMinFrameSize, s.maxTextureSize);
  checkMemory(settings, light);
}

void Renderer::checkMemory(const RenderSettings& settings, LightKind light) const {
  const State& s = *state_;
  const MemoryBudget budget = memoryBudget(s);
  const int maxLayers = s.limits.maxArrayLayers;
  // The uploaded scene's vertex, index and texture storage shares the budget with the render's.
  const uint64_t sceneBytes = s.scene ? s.scene->bytes() : 0;
  const std::string shortfall = memoryShortfall(settings, budget, maxLayers, light, sceneBytes);
  if (shortfall.empty()) return;
  // The largest shadow-map size that fits with everything else unchanged (all allocations grow
  // with it, so the search is monotone).
  auto fits = [&](int size) {
    RenderSettings smaller = settings;
    smaller.shadowMapSize = size;
    return memoryShortfall(smaller, budget, maxLayers, light, sceneBytes).empty();
  };
  std::string advice = "no shadow-map size fits with this frame size";
  if (sceneBytes >= budget.bytes) {
    advice = "the scene's geometry and textures alone take " + gib(sceneBytes) + " (" +
             std::to_string(sceneBytes) + " bytes)";
  } else if (fits(16)) {
    int lo = 16, hi = settings.shadowMapSize;  // fits(lo), !fits(hi)
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (fits(mid) ? lo : hi) = mid;
    }
    advice = "the largest shadow-map size that fits is " + std::to_string(lo);
  }
  const uint64_t need = estimateMemory(settings, light).total() + sceneBytes;
  throw Error(std::string(techniqueId(settings.technique)) + " at shadow-map size " +
              std::to_string(settings.shadowMapSize) + " (frame " + std::to_string(settings.width) +
              "x" + std::to_string(settings.height) +
              (settings.msaaSamples > 1 ? ", " + std::to_string(settings.msaaSamples) + "x MSAA"
                                        : std::string()) +
              ") needs " + gib(need) + " (" + std::to_string(need) + " bytes" +
              (sceneBytes > 0 ? ", the scene's " + std::to_string(sceneBytes) + " included"
                              : std::string()) +
              "), and " + shortfall + "; " + advice);
}

}  // namespace penumbra::gl
