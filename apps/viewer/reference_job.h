// The error view's filtered reference, computed off the main thread so the window never waits
// for it: a snapshot of one render's lookup inputs and light-pass depth maps (read back on the
// main thread, the only one that calls GL) goes to a background thread, which evaluates the
// library's CPU reference (penumbra/shadow_lookup.h, the twin of Renderer::renderReference) row
// by row. The window shows the rows done so far; a new render replaces the job, which stops.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "penumbra/gl/renderer.h"
#include "penumbra/image.h"

namespace penumbra::viewer {

class ReferenceJob {
 public:
  // `result` and `depthMaps` (Renderer::readDepthMap per cascade) are of the same render of
  // `settings`; `halfRounding` is the renderer's (Renderer::halfFloatRounding). Starts at once.
  ReferenceJob(std::shared_ptr<const gl::RenderResult> result,
               std::shared_ptr<const std::vector<Image>> depthMaps,
               const gl::RenderSettings& settings, HalfRounding halfRounding);
  // Stops the thread (it checks between pixels) and waits for it.
  ~ReferenceJob();
  // Asks the thread to stop without waiting; finished() tells when it has.
  void stop();
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  ReferenceJob(const ReferenceJob&) = delete;
  ReferenceJob& operator=(const ReferenceJob&) = delete;

  // Rows of the frame done, from the top; all of them once complete.
  int rowsDone() const { return rowsDone_.load(std::memory_order_acquire); }
  int rows() const { return reference_.height(); }
  bool complete() const { return rowsDone() == rows(); }
  // The reference's visibility, row 0 at the top: rows below rowsDone() are 0.
  Image snapshot() const;
  // Why it stopped (an Error's message); empty while it runs or once complete.
  std::string failure() const;
  // Seconds from the start to completion (or until now while it runs).
  double seconds() const;

 private:
  void compute(const std::stop_token& stop);

  // The lookup inputs (lookup, receiver plane, derivatives, cascades) and depth maps, as rendered.
  std::shared_ptr<const gl::RenderResult> result_;
  std::shared_ptr<const std::vector<Image>> depthMaps_;
  gl::RenderSettings settings_;
  HalfRounding halfRounding_;
  Image reference_;  // rows [0, rowsDone_) written by the thread, then only read
  std::atomic<int> rowsDone_{0};
  std::chrono::steady_clock::time_point start_;
  std::atomic<double> seconds_{-1.0};
  mutable std::mutex failureMutex_;
  std::string failure_;
  std::atomic<bool> finished_{false};
  std::jthread thread_;  // last: started once everything above is in place
};

}  // namespace penumbra::viewer
