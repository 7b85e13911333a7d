// The true shadow on a background thread.
#include "true_shadow_job.h"

#include <exception>

#include "penumbra/error.h"

namespace penumbra::viewer {

RaySceneSlot::RaySceneSlot(Scene scene) : scene_(std::move(scene)) {}

std::shared_ptr<const truth::RayScene> RaySceneSlot::get(const std::stop_token& stop) {
  std::unique_lock lock(mutex_);
  if (!rayScene_ && failure_.empty() && !building_) {
    building_ = true;
    Scene source = std::move(*scene_);
    scene_.reset();
    lock.unlock();
    std::shared_ptr<const truth::RayScene> built;
    std::string failure;
    try {
      built = std::make_shared<const truth::RayScene>(source);
    } catch (const std::exception& e) {  // Error, or memory running out
      failure = e.what();
    }
    lock.lock();
    rayScene_ = std::move(built);
    failure_ = std::move(failure);
    building_ = false;
    built_.notify_all();
  }
  built_.wait(lock, stop, [this] { return !building_; });
  if (!failure_.empty()) throw Error("building the scene's ray-tracing BVH failed: " + failure_);
  return rayScene_;  // nullptr when stopped while another job builds it
}

size_t RaySceneSlot::triangleCount() const {
  std::lock_guard lock(mutex_);
  return rayScene_ ? rayScene_->triangleCount() : 0;
}

double RaySceneSlot::buildSeconds() const {
  std::lock_guard lock(mutex_);
  return rayScene_ ? rayScene_->buildSeconds() : 0.0;
}

TrueShadowJob::TrueShadowJob(std::shared_ptr<RaySceneSlot> slot,
                             const truth::TrueShadowRequest& request, Image rasterWindowDepth)
    : slot_(std::move(slot)),
      request_(request),
      rasterWindowDepth_(std::move(rasterWindowDepth)),
      start_(std::chrono::steady_clock::now()),
      thread_([this](std::stop_token stop) {
        compute(stop);
        finished_.store(true, std::memory_order_release);
      }) {}

TrueShadowJob::~TrueShadowJob() {
  thread_.request_stop();
  // jthread joins here.
}

void TrueShadowJob::stop() {
  thread_.request_stop();
}

std::string TrueShadowJob::failure() const {
  std::lock_guard lock(failureMutex_);
  return failure_;
}

double TrueShadowJob::seconds() const {
  const double done = seconds_.load(std::memory_order_acquire);
  if (done >= 0.0) return done;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void TrueShadowJob::compute(const std::stop_token& stop) {
  try {
    const std::shared_ptr<const truth::RayScene> scene = slot_->get(stop);
    if (!scene || stop.stop_requested()) return;
    sceneReady_.store(true, std::memory_order_release);
    truth::TraceControl control;
    control.stopRequested = [&stop] { return stop.stop_requested(); };
    control.rowsDone = &rowsDone_;
    std::optional<truth::TrueShadow> trace = truth::traceTrueShadow(*scene, request_, control);
    if (!trace) return;
    match_ = truth::matchRasterisedSurfaces(*trace, rasterWindowDepth_, request_);
    trace_ = std::move(*trace);
    seconds_.store(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(),
                   std::memory_order_release);
    complete_.store(true, std::memory_order_release);
  } catch (const std::exception& e) {  // Error, or memory running out
    std::lock_guard lock(failureMutex_);
    failure_ = e.what();
  }
}

}  // namespace penumbra::viewer
