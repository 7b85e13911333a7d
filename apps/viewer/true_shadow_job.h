// The error-against-the-true-shadow view's ray tracing, off the main thread so the window never
// waits for it: the scene's Embree BVH (penumbra/truth/true_shadow.h) is built once per loaded
// scene by the first job that needs it, then every camera or light change traces the frame on a
// background thread and matches its surfaces against the render's camera depth (read on the main
// thread, the only one that calls GL). A new view replaces the job, which stops between rows.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>

#include "penumbra/image.h"
#include "penumbra/scene.h"
#include "penumbra/truth/true_shadow.h"

namespace penumbra::viewer {

// One scene's BVH, shared by the jobs of that scene: the first job to ask builds it (an Embree
// build cannot be interrupted, so it completes even when its job is stopped), the others wait.
class RaySceneSlot {
 public:
  explicit RaySceneSlot(Scene scene);
  // The BVH, built by this call or by another job's; nullptr once `stop` is requested while
  // waiting. Throws the build's Error (again for every caller).
  std::shared_ptr<const truth::RayScene> get(const std::stop_token& stop);
  // Once built: its triangles and build time (0 before).
  size_t triangleCount() const;
  double buildSeconds() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable_any built_;
  std::optional<Scene> scene_;  // the source until the build takes it
  bool building_ = false;
  std::shared_ptr<const truth::RayScene> rayScene_;
  std::string failure_;
};

class TrueShadowJob {
 public:
  // `rasterWindowDepth` is Renderer::readCameraDepth of the render of `request`'s camera and
  // frame size (supersample 1). Starts at once.
  TrueShadowJob(std::shared_ptr<RaySceneSlot> slot, const truth::TrueShadowRequest& request,
                Image rasterWindowDepth);
  // Stops the thread (between rows, or once the BVH it builds is done) and waits for it.
  ~TrueShadowJob();
  TrueShadowJob(const TrueShadowJob&) = delete;
  TrueShadowJob& operator=(const TrueShadowJob&) = delete;
  // Asks the thread to stop without waiting; finished() tells when it has.
  void stop();
  bool finished() const { return finished_.load(std::memory_order_acquire); }

  const truth::TrueShadowRequest& request() const { return request_; }
  const std::shared_ptr<RaySceneSlot>& slot() const { return slot_; }
  bool sceneReady() const { return sceneReady_.load(std::memory_order_acquire); }
  int rowsDone() const { return rowsDone_.load(std::memory_order_acquire); }
  int rows() const { return request_.height; }
  bool complete() const { return complete_.load(std::memory_order_acquire); }
  // Once complete (the thread no longer writes them): the trace and its surface match.
  const truth::TrueShadow& trace() const { return trace_; }
  const truth::SurfaceMatch& match() const { return match_; }
  // Why it stopped (an Error's message); empty while it runs or once complete.
  std::string failure() const;
  // Seconds from the start to completion (or until now while it runs).
  double seconds() const;

 private:
  void compute(const std::stop_token& stop);

  std::shared_ptr<RaySceneSlot> slot_;
  truth::TrueShadowRequest request_;
  Image rasterWindowDepth_;
  truth::TrueShadow trace_;
  truth::SurfaceMatch match_;
  std::atomic<bool> sceneReady_{false};
  std::atomic<int> rowsDone_{0};
  std::atomic<bool> complete_{false};
  std::chrono::steady_clock::time_point start_;
  std::atomic<double> seconds_{-1.0};
  mutable std::mutex failureMutex_;
  std::string failure_;
  std::atomic<bool> finished_{false};
  std::jthread thread_;  // last: started once everything above is in place
};

}  // namespace penumbra::viewer
