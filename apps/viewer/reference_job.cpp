// The filtered reference on a background thread.
#include "reference_job.h"

#include <map>
#include <memory>

#include "penumbra/error.h"
#include "penumbra/metrics.h"
#include "penumbra/shadow_lookup.h"

namespace penumbra::viewer {

ReferenceJob::ReferenceJob(std::shared_ptr<const gl::RenderResult> result,
                           std::shared_ptr<const std::vector<Image>> depthMaps,
                           const gl::RenderSettings& settings, HalfRounding halfRounding)
    : result_(std::move(result)),
      depthMaps_(std::move(depthMaps)),
      settings_(settings),
      halfRounding_(halfRounding),
      reference_(result_->visibility.width(), result_->visibility.height(), 1),
      start_(std::chrono::steady_clock::now()),
      thread_([this](std::stop_token stop) {
        compute(stop);
        finished_.store(true, std::memory_order_release);
      }) {}

void ReferenceJob::stop() {
  thread_.request_stop();
}

ReferenceJob::~ReferenceJob() {
  thread_.request_stop();
  // jthread joins here; the thread checks for the stop between pixels.
}

Image ReferenceJob::snapshot() const {
  const int done = rowsDone();
  Image copy(reference_.width(), reference_.height(), 1);
  for (int y = 0; y < done; ++y) {
    for (int x = 0; x < reference_.width(); ++x) copy.at(x, y) = reference_.at(x, y);
  }
  return copy;
}

std::string ReferenceJob::failure() const {
  std::lock_guard lock(failureMutex_);
  return failure_;
}

double ReferenceJob::seconds() const {
  const double done = seconds_.load(std::memory_order_acquire);
  if (done >= 0.0) return done;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

// Per pixel what Renderer::renderReference gives (its CPU completion, Renderer::
// completeReferenceOnCpu, runs the same twin for the pixels the GPU leaves): the cascade's twin,
// blended with the next cascade's in the blend band.
void ReferenceJob::compute(const std::stop_token& stop) {
  try {
    const gl::RenderResult& r = *result_;
    const std::vector<Image>& depthMaps = *depthMaps_;
    const int size = settings_.shadowMapSize;
    std::map<int, std::unique_ptr<CpuShadowLookup>> twins;
    auto twin = [&](int cascade) -> const CpuShadowLookup& {
      std::unique_ptr<CpuShadowLookup>& found = twins[cascade];
      if (!found) {
        if (size_t(cascade) >= depthMaps.size() || size_t(cascade) >= r.cascadeBlurs.size()) {
          throw Error("the render has no depth map for cascade " + std::to_string(cascade));
        }
        found = std::make_unique<CpuShadowLookup>(
            depthMaps[size_t(cascade)],
            LookupConfig{Technique::Hard, r.params, settings_.filter,
                         r.cascadeBlurs[size_t(cascade)], settings_.anisotropy, halfRounding_,
                         r.cascadeFrame.kernelScale(cascade, size)});
      }
      return *found;
    };
    // Only where the shadow test decides the shading: the error view shows 0 elsewhere.
    const Image covered = litSurfaceMask(r.lookup);
    const CascadeFrame& cascades = r.cascadeFrame;
    for (int y = 0; y < reference_.height(); ++y) {
      for (int x = 0; x < reference_.width(); ++x) {
        if (stop.stop_requested()) return;
        const int cascade = int(r.cascades.at(x, y, 0));
        if (covered.at(x, y) == 0.0f || cascade < 0) {
          reference_.at(x, y) = r.visibility.at(x, y);
          continue;
        }
        const float blend = r.cascades.at(x, y, 1);
        const LookupPixel pixel = gl::lookupPixelAt(r, x, y);
        float v = twin(cascade).referenceVisibility(pixel);
        if (blend > 0.0f && cascade + 1 < cascades.count) {
          const LookupPixel other = gl::lookupPixelInNextCascade(pixel, cascades, cascade, size);
          v = glm::mix(v, twin(cascade + 1).referenceVisibility(other), blend);
        }
        reference_.at(x, y) = v;
      }
      rowsDone_.store(y + 1, std::memory_order_release);
    }
    seconds_.store(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(),
                   std::memory_order_release);
  } catch (const std::exception& e) {  // Error, or memory running out
    std::lock_guard lock(failureMutex_);
    failure_ = e.what();
  }
}

}  // namespace penumbra::viewer
