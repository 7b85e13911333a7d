// The filtered reference on a background thread.
#include "reference_job.h"

#include <map>
#include <memory>

#include "penumbra/error.h"
#include "penumbra/gl/cascaded_reference.h"
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

// Per pixel what Renderer::renderReference gives: gl::CascadedReference, which the renderer's
// completion of the pixels the GPU leaves (Renderer::completeReferenceOnCpu) runs too.
void ReferenceJob::compute(const std::stop_token& stop) {
  try {
    const gl::RenderResult& r = *result_;
    const std::vector<Image>& depthMaps = *depthMaps_;
    gl::CascadedReference reference(
        r, settings_.shadowMapSize, settings_.filter, settings_.anisotropy, halfRounding_,
        [&depthMaps](int cascade) {
          if (size_t(cascade) >= depthMaps.size()) {
            throw Error("the render has no depth map for cascade " + std::to_string(cascade));
          }
          return depthMaps[size_t(cascade)];
        });
    // Only where the shadow test decides the shading: the error view shows 0 elsewhere.
    const Image covered = litSurfaceMask(r.lookup);
    for (int y = 0; y < reference_.height(); ++y) {
      for (int x = 0; x < reference_.width(); ++x) {
        if (stop.stop_requested()) return;
        const int cascade = int(r.cascades.at(x, y, 0));
        if (covered.at(x, y) == 0.0f || cascade < 0) {
          reference_.at(x, y) = r.visibility.at(x, y);
          continue;
        }
        reference_.at(x, y) = reference.visibilityAt(x, y);
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
