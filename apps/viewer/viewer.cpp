// The viewer's loop.
#include "viewer.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <iostream>
#include <memory>
#include <optional>

#include "cursor_probe.h"
#include "display_image.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/image_io.h"
#include "reference_job.h"
#include "scene_texture.h"
#include "settings_panel.h"
#include "true_shadow_job.h"
#include "viewer_state.h"
#include "viewer_window.h"

namespace penumbra::viewer {
namespace {

constexpr float kPanelWidth = 430.0f;
constexpr size_t kTimeHistory = 120;  // frames in the rolling time graph
// Waits for events between frames: while the reference computes, often enough to show its
// progress; idle, long (any event wakes the window at once).
constexpr double kProgressWaitSeconds = 1.0 / 30.0;
constexpr double kIdleWaitSeconds = 0.25;
// Fly mode: W A S D Q E move this many scene radii per second; one frame moves at most this
// long's worth (a frame stalled by a shader compile must not throw the camera out of the scene).
constexpr float kFlySpeedRadiiPerSecond = 0.5f;
constexpr float kLongestFlyStepSeconds = 0.25f;
// The error view shows the reference's new rows at most this often (and once complete).
constexpr double kProgressRefreshSeconds = 0.1;
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void setMessage(ViewerState& state, std::string message, bool isError) {
  state.message = std::move(message);
  state.messageIsError = isError;
}

void loadSceneInto(ViewerState& state, SceneLoadOptions options) {
  options.aspect = float(state.settings.render.width) / float(state.settings.render.height);
  options.ground = state.settings.ground;
  options.casters = state.settings.casters;
  Scene scene = loadScene(state.settings.scene, options);
  applyOverrides(scene, state.settings.view);
  for (const std::string& w : scene.warnings)
    std::cerr << "penumbra-viewer: warning: " << w << "\n";
  for (const std::string& n : scene.notes) std::cerr << "penumbra-viewer: note: " << n << "\n";
  state.scene = std::move(scene);
  state.clipSeconds = 0.0f;  // a scene file's clip starts again
  state.camera = state.scene.camera;
  state.light = state.scene.light;
  if (state.light.kind != LightKind::Directional) state.settings.render.cascades.count = 1;
}

class Viewer {
 public:
  Viewer(const ViewerOptions& options, gl::Settings settings, ViewerWindow& window)
      : options_(options), window_(window), renderer_(context_) {
    state_.settings = std::move(settings);
    takeSplitSettings(state_);
    state_.showPanel = !options.hidePanel;
    if (options.fly) state_.cameraMode = CameraMode::Fly;
    state_.view = parseView(options.show);
    if (options.probeX >= 0 && options.probeY >= 0) probePixel_ = {options.probeX, options.probeY};
    if (!options.split.empty()) {
      state_.split = true;
      state_.splitTechnique = parseTechnique(options.split);
      state_.splitParams = state_.settings.render.params;
    }
    if (!options.settingsFile.empty()) state_.settingsPath = options.settingsFile;
    loadSceneInto(state_, options_.sceneLoad);
    renderer_.setScene(state_.scene);
  }

  void run() {
    int frame = 0;
    bool renderNeeded = true;
    bool displayNeeded = true;
    int idleFrames = 0;
    while (!window_.shouldClose()) {
      // Scripted runs draw without waiting, but for the reference's progress; interactive ones
      // sleep once nothing has moved for two frames (ImGui settles in one).
      const bool pending = referencePending() || truthPending();
      const bool waitingForProbe = probeJob_.valid() || (options_.frames > 0 && probePending());
      const double wait = pending || waitingForProbe                ? kProgressWaitSeconds
                          : options_.frames == 0 && idleFrames >= 2 ? kIdleWaitSeconds
                                                                    : 0.0;
      window_.beginFrame(wait);
      const bool probeWasRunning = probeJob_.valid();
      const Clock::time_point frameStart = Clock::now();
      Changes changes;
      if (state_.showPanel) {
        FrameStats stats{result_ ? &*result_ : nullptr, renderer_.deviceDescription()};
        changes = drawSettingsPanel(state_, stats, kPanelWidth);
      }
      bool moving = false;
      if (options_.frames == 0) moving = handleInput(changes);  // scripted runs take no input
      applyFileChanges(changes);
      if (changes.scene) {
        if (tryOrReport([&] {
              SceneLoadOptions reload = options_.sceneLoad;
              reload.camera.reset();  // --camera named a camera of the first scene
              loadSceneInto(state_, reload);
              renderer_.setScene(state_.scene);
              forgetRayScene();
            })) {
          renderNeeded = true;
        }
      }
      if (advanceClip(changes, frame)) {
        tryOrReport([&] {
          poseScene(state_.scene, state_.clipSeconds);
          renderer_.setScene(state_.scene);  // the new pose's vertices
          forgetRayScene();                  // the truth traces the new pose
        });
        renderNeeded = true;
      }
      renderNeeded |= changes.render;
      const bool rendered = renderNeeded;
      if (renderNeeded) {
        renderFrame();
        renderNeeded = false;
        displayNeeded = true;
      }
      displayNeeded |= followReference();
      displayNeeded |= followTruth();
      if (displayNeeded || changes.display) {
        showDisplay();
        displayNeeded = false;
      }
      updateProbe();
      drawWindow();
      ++frame;
      // Scripted runs end once the error view shows its complete reference and the probe its
      // pixel's curves.
      const bool lastScripted = options_.frames > 0 && frame >= options_.frames &&
                                referenceOnScreen() && truthOnScreen() && !probePending();
      if (lastScripted && referenceJob_ && referenceJob_->complete()) {
        followReference();  // the status of the complete reference
        std::cout << "penumbra-viewer: " << state_.referenceStatus << "\n";
      }
      if (lastScripted && state_.view == View::TrueError && truthShown_) {
        std::cout << "penumbra-viewer: " << state_.truthStatus << "\n";
      }
      if (lastScripted && !options_.screenshot.empty()) writeScreenshot(options_.screenshot);
      if (lastScripted && !options_.saveSettings.empty()) {
        gl::writeSettingsFile(options_.saveSettings, settingsToSave(state_));
      }
      if (screenshotRequested_) {
        screenshotRequested_ = false;
        char name[64];
        std::snprintf(name, sizeof name, "penumbra-viewer-%04d.png", screenshotCount_++);
        tryOrReport([&] {
          writeScreenshot(name);
          setMessage(state_, std::string("wrote ") + name, false);
        });
      }
      window_.swapBuffers();
      const double frameMs = millisecondsSince(frameStart);
      recordFrameTime(frameMs, pending && !rendered);
      if (probeWasRunning && probeJob_.valid() && !rendered) {
        ++probeFrames_;
        longestProbeFrameMs_ = std::max(longestProbeFrameMs_, frameMs);
      }
      const bool idle =
          !rendered && !changes.display && !changes.scene && !moving && !ImGui::IsAnyMouseDown();
      idleFrames = idle ? idleFrames + 1 : 0;
      truthDescribed_ = truthShown_;
      if (lastScripted) break;
    }
  }

 private:
  // Runs f; an Error becomes the panel's message (and, scripted, fails the run).
  template <typename F>
  bool tryOrReport(F&& f) {
    try {
      f();
      return true;
    } catch (const Error& e) {
      if (options_.frames > 0) throw;
      setMessage(state_, e.what(), true);
      return false;
    }
  }

  gl::RenderSettings currentSettings() const {
    gl::RenderSettings s = state_.settings.render;
    s.technique = state_.settings.techniques.front();
    s.lookupInputs = true;  // the cursor probe and the error views read them
    return s;
  }

  gl::FrameView currentView() const { return gl::FrameView{state_.camera, state_.light}; }

  void renderFrame() {
    const gl::RenderSettings settings = currentSettings();
    tryOrReport([&] {
      renderer_.validate(settings);
      requireCascadableLight(settings.cascades, state_.light);
      if (state_.split) {
        // The right side first: the renderer then holds the left side's maps, which the shadow
        // map and channel views and the probe's depth maps read.
        gl::RenderSettings right = settings;
        right.technique = state_.splitTechnique;
        right.params = state_.splitParams;
        renderer_.validate(right);
        splitResult_ =
            std::make_shared<const gl::RenderResult>(renderer_.render(right, currentView()));
      } else {
        splitResult_.reset();
      }
      result_ = std::make_shared<const gl::RenderResult>(renderer_.render(settings, currentView()));
      resultView_ = currentView();
      ++renderGeneration_;
      // GPU times where the device's timer queries measure them, for every frame kept.
      if (result_->gpuTimes) {
        state_.gpuTimes.push_back(*result_->gpuTimes);
      } else {
        state_.gpuTimes.clear();
      }
      if (result_->wallTimes) state_.wallTimes.push_back(*result_->wallTimes);
      if (state_.wallTimes.size() > kTimeHistory) state_.wallTimes.pop_front();
      if (state_.gpuTimes.size() > kTimeHistory) state_.gpuTimes.pop_front();
      resultSettings_ = settings;
      // A trace of another camera, light or frame size stops (the view starts the next one).
      if (truthJob_ && !sameTrueShadowView(truthJob_->request(), trueShadowRequest())) {
        retireTruthJob();
      }
      truthShown_ = false;  // the new render's error is composed once the trace is complete
      // The reference is started again when the error view asks for it; a running one stops,
      // retired so the window never waits for it (a twin being built checks no stop token).
      retireReferenceJob();
      reference_.reset();
      referenceRowsShown_ = -1;
      depthMaps_.reset();  // read again when the probe or the reference needs them
      if (state_.messageIsError) state_.message.clear();
    });
  }

  // The error view's reference: none yet, or not yet complete.
  bool referencePending() const {
    return state_.view == View::Error && result_ &&
           (!referenceJob_ || (!referenceJob_->complete() && referenceJob_->failure().empty()));
  }

  // Whether the error view shows its complete reference (it may complete between the frame's
  // look at it and the screenshot: the next frame shows it).
  bool referenceOnScreen() const {
    return state_.view != View::Error || !result_ ||
           (referenceJob_ &&
            (!referenceJob_->failure().empty() || referenceRowsShown_ == referenceJob_->rows()));
  }

  // Starts the reference of the last render on the background thread, from the render's lookup
  // inputs and its depth maps read back here (GL stays on this thread).
  void startReference() {
    readDepthMaps();
    referenceJob_ = std::make_unique<ReferenceJob>(result_, depthMaps_, resultSettings_,
                                                   renderer_.halfFloatRounding());
    referenceRowsShown_ = -1;
    pendingFrames_ = 0;
    longestPendingFrameMs_ = 0.0;
  }

  // Whether the reference has new rows to show (at most every kProgressRefreshSeconds, and once
  // complete); keeps the panel's status line and reports a failure.
  bool followReference() {
    if (state_.view != View::Error || !referenceJob_) return false;
    const ReferenceJob& job = *referenceJob_;
    const int rows = job.rowsDone();
    char status[160];
    if (!job.failure().empty()) {
      if (options_.frames > 0) throw Error("the filtered reference failed: " + job.failure());
      if (!state_.messageIsError) setMessage(state_, job.failure(), true);
      state_.referenceStatus = "filtered reference failed";
      return false;
    }
    if (job.complete()) {
      std::snprintf(status, sizeof status,
                    "filtered reference: %.0f ms on a background thread; %d frames drawn "
                    "meanwhile, the longest %.1f ms",
                    job.seconds() * 1000.0, pendingFrames_, longestPendingFrameMs_);
    } else {
      std::snprintf(status, sizeof status, "computing the filtered reference... %d%% (%.1f s)",
                    100 * rows / std::max(job.rows(), 1), job.seconds());
    }
    state_.referenceStatus = status;
    if (rows == referenceRowsShown_) return false;
    return job.complete() ||
           std::chrono::duration<double>(Clock::now() - referenceShownAt_).count() >=
               kProgressRefreshSeconds;
  }

  // The error against the true shadow: nothing traced yet for the render's view, or not yet
  // complete.
  bool truthPending() const {
    return state_.view == View::TrueError && result_ &&
           (!truthJob_ || (!truthJob_->complete() && truthJob_->failure().empty()));
  }

  // Whether the view shows the complete trace (or its failure), the panel its numbers: a frame
  // after the one that composed it, whose panel was drawn before.
  bool truthOnScreen() const {
    return state_.view != View::TrueError || !result_ ||
           (truthJob_ && (!truthJob_->failure().empty() || (truthShown_ && truthDescribed_)));
  }

  // What the trace of the last render is: its camera, light and frame size, one sample per pixel
  // (the frame's own pixels, as the render's camera depth is), the light's size with the
  // default sample count.
  truth::TrueShadowRequest trueShadowRequest() const {
    truth::TrueShadowRequest request;
    request.camera = resultView_.camera;
    request.light = resultView_.light;
    request.viewBounds = state_.scene.viewBounds();
    request.width = resultSettings_.width;
    request.height = resultSettings_.height;
    request.supersample = 1;
    request.lightSamples = truth::kDefaultTrueShadowLightSamples;
    request.ambient = resultSettings_.ambient;
    return request;
  }

  static bool sameTrueShadowView(const truth::TrueShadowRequest& a,
                                 const truth::TrueShadowRequest& b) {
    const auto sameCamera = [](const Camera& p, const Camera& q) {
      return p.position == q.position && p.target == q.target &&
             p.verticalFovDegrees == q.verticalFovDegrees;
    };
    const auto sameLight = [](const Light& p, const Light& q) {
      return p.kind == q.kind && p.direction == q.direction && p.position == q.position &&
             p.target == q.target && p.spotAngleDegrees == q.spotAngleDegrees && p.size == q.size;
    };
    return sameCamera(a.camera, b.camera) && sameLight(a.light, b.light) && a.width == b.width &&
           a.height == b.height && a.supersample == b.supersample &&
           a.lightSamples == b.lightSamples;
  }

  // A new scene: its BVH is built again when the view needs it.
  // Moves the clip time on while the scene's animation plays (by the time since the last frame;
  // scripted runs by a frame's worth of the clip, holding still after their last frame so that
  // its references finish); whether the scene needs posing.
  bool advanceClip(const Changes& changes, int frame) {
    const SceneAnimation& animation = state_.scene.animation;
    if (!animation.moves()) return false;
    const Clock::time_point now = Clock::now();
    const double elapsed =
        clipClock_ ? std::chrono::duration<double>(now - *clipClock_).count() : 0.0;
    clipClock_ = now;
    const bool scripted = options_.frames > 0;
    if (!state_.playing || changes.scene || (scripted && frame >= options_.frames)) {
      return changes.pose || changes.scene;
    }
    // Scripted frame f shows the clip at f / 30 s, as render --frames does.
    state_.clipSeconds =
        scripted ? clipTime(state_.scene, frame)
                 : float(std::fmod(state_.clipSeconds + elapsed, double(animation.duration)));
    return true;
  }

  void forgetRayScene() {
    retireTruthJob();
    raySceneSlot_.reset();
  }

  void retireTruthJob() {
    std::erase_if(retiredTruthJobs_, [](const auto& job) { return job->finished(); });
    truthShown_ = false;
    if (!truthJob_) return;
    truthJob_->stop();
    retiredTruthJobs_.push_back(std::move(truthJob_));
  }

  // Starts the trace of the last render's view unless it is running or done: the camera depth
  // is read here, right after the render (GL stays on this thread).
  void startTruthIfNeeded() {
    if (!raySceneSlot_) raySceneSlot_ = std::make_shared<RaySceneSlot>(state_.scene);
    const truth::TrueShadowRequest request = trueShadowRequest();
    if (truthJob_ && truthJob_->slot() == raySceneSlot_ &&
        sameTrueShadowView(truthJob_->request(), request)) {
      return;
    }
    retireTruthJob();
    truthJob_ =
        std::make_unique<TrueShadowJob>(raySceneSlot_, request, renderer_.readCameraDepth());
    truthFrames_ = 0;
    longestTruthFrameMs_ = 0.0;
  }

  // Whether the trace has just completed (the view composes it then); keeps the status line
  // while it runs and reports a failure.
  bool followTruth() {
    if (state_.view != View::TrueError || !truthJob_) return false;
    const TrueShadowJob& job = *truthJob_;
    if (!job.failure().empty()) {
      if (options_.frames > 0) throw Error("the true shadow failed: " + job.failure());
      if (!state_.messageIsError) setMessage(state_, job.failure(), true);
      state_.truthStatus = "the true shadow failed";
      return false;
    }
    if (job.complete()) return !truthShown_;
    char status[160];
    if (!job.sceneReady()) {
      std::snprintf(status, sizeof status, "building the scene's ray-tracing BVH... (%.1f s)",
                    job.seconds());
    } else {
      std::snprintf(status, sizeof status, "tracing the true shadow... %d%% (%.1f s)",
                    100 * job.rowsDone() / std::max(job.rows(), 1), job.seconds());
    }
    state_.truthStatus = status;
    return false;
  }

  // The panel's lines for a complete trace: its cost, the silhouettes left out, the errors.
  void describeTruth(const TrueShadowFrame& truth) {
    const TrueShadowJob& job = *truthJob_;
    const VisibilityErrors errors = measureAgainstTrueShadow(*result_, truth);
    char status[512];
    std::snprintf(
        status, sizeof status,
        "true shadow: %.0f ms on a background thread; %d frames drawn meanwhile, the longest "
        "%.1f ms (BVH of %zu triangles built in %.0f ms, %llu shadow rays)\n"
        "silhouettes: %d pixels not measured (the render sees another surface)\n"
        "%s against it over %d pixels: RMSE %.4f, max %.3f, leaks light %.2f%%, over-darkens "
        "%.2f%% (beyond %.2f)",
        job.seconds() * 1000.0, truthFrames_, longestTruthFrameMs_, job.slot()->triangleCount(),
        job.slot()->buildSeconds() * 1000.0,
        static_cast<unsigned long long>(truth.trace.shadowRays), truth.match.excludedPixels,
        std::string(techniqueId(resultSettings_.technique)).c_str(), errors.pixels, errors.rmse,
        errors.maxAbsolute, 100.0 * errors.leakShare, 100.0 * errors.darkShare, 0.05);
    state_.truthStatus = status;
  }

  void recordFrameTime(double ms, bool whileReferencePending) {
    state_.frameMs.push_back(ms);
    if (state_.frameMs.size() > kTimeHistory) state_.frameMs.pop_front();
    if (whileReferencePending && truthJob_ && !truthJob_->complete()) {
      ++truthFrames_;
      longestTruthFrameMs_ = std::max(longestTruthFrameMs_, ms);
    }
    if (whileReferencePending && referenceJob_ && !referenceJob_->complete()) {
      ++pendingFrames_;
      longestPendingFrameMs_ = std::max(longestPendingFrameMs_, ms);
    }
  }

  void readDepthMaps() {
    if (depthMaps_ || !result_) return;
    std::vector<Image> maps;
    for (int c = 0; c < result_->cascadeFrame.count; ++c) maps.push_back(renderer_.readDepthMap(c));
    depthMaps_ = std::make_shared<const std::vector<Image>>(std::move(maps));
  }

  void showDisplay() {
    if (!result_) return;
    tryOrReport([&] {
      std::optional<Image> map;
      if (state_.view == View::Error) {
        // The filtered reference of the same settings and view, computed on a background thread
        // once per rendered frame; until it is complete the rows done so far.
        if (!referenceJob_) startReference();
        const int rows = referenceJob_->rowsDone();
        if (rows != referenceRowsShown_) {
          reference_ = referenceJob_->snapshot();
          referenceRowsShown_ = rows;
          referenceShownAt_ = Clock::now();
        }
      }
      std::optional<TrueShadowFrame> truth;
      if (state_.view == View::TrueError) {
        // The trace of the render's camera and light, on a background thread once per view
        // (a technique or setting change reuses it); until it is complete the dimmed visibility.
        startTruthIfNeeded();
        if (truthJob_->complete()) {
          truth.emplace(TrueShadowFrame{truthJob_->trace(), truthJob_->match()});
          if (!truthShown_) describeTruth(*truth);
          truthShown_ = true;
        }
      }
      const TrueShadowFrame* truthShown = truth ? &*truth : nullptr;
      const int cascade = std::clamp(state_.mapCascade, 0, result_->cascadeFrame.count - 1);
      if (state_.view == View::ShadowMap) map = renderer_.readDepthMap(cascade);
      if (state_.view == View::Channel) {
        const Image channels = renderer_.readChannels(0, cascade);
        const int c = std::clamp(state_.channel, 0, channels.channels() - 1);
        map.emplace(channels.width(), channels.height(), 1);
        for (int y = 0; y < channels.height(); ++y) {
          for (int x = 0; x < channels.width(); ++x) map->at(x, y) = channels.at(x, y, c);
        }
      }
      const Image* reference = reference_ ? &*reference_ : nullptr;
      DisplayImage image = composeDisplay(state_.view, *result_, reference, map ? &*map : nullptr,
                                          referenceRowsShown_, truthShown);
      if (splitResult_ && !map) {
        // The same view of the right side's render (the reference does not depend on the
        // technique), right of the divider.
        const DisplayImage right = composeDisplay(state_.view, *splitResult_, reference, nullptr,
                                                  referenceRowsShown_, truthShown);
        const size_t from = size_t(dividerPixel()) * 3;
        const size_t row = size_t(image.width) * 3;
        for (int y = 0; y < image.height; ++y) {
          std::copy(right.rgb.begin() + std::ptrdiff_t(size_t(y) * row + from),
                    right.rgb.begin() + std::ptrdiff_t(size_t(y + 1) * row),
                    image.rgb.begin() + std::ptrdiff_t(size_t(y) * row + from));
        }
      }
      texture_.upload(image);
    });
  }

  // The probe of the pixel under the cursor, computed on a background thread when the pixel or
  // the render changes (the curves of every technique take a good part of a second on llvmpipe's
  // machine): the window shows the last probe until the new one lands. One runs at a time; when
  // it lands, the next starts for wherever the cursor is then.
  void updateProbe() {
    using namespace std::chrono_literals;
    if (probeJob_.valid() && probeJob_.wait_for(0s) == std::future_status::ready) {
      const bool landed = tryOrReport([&] {
        CursorProbe probe = probeJob_.get();  // rethrows the job's Error
        if (options_.frames > 0 && probeOf_.x < 0) {
          // The scripted run's probe: how long it took, and that the window went on meanwhile.
          std::printf(
              "penumbra-viewer: cursor probe: %.0f ms on a background thread; %d frames drawn "
              "meanwhile, the longest %.1f ms\n",
              millisecondsSince(probeStarted_), probeFrames_, longestProbeFrameMs_);
          std::fflush(stdout);
        }
        probe_ = std::move(probe);
      });
      if (!landed) {  // it threw: the pixel says why, and is not tried again until it changes
        probe_ = CursorProbe{};
        probe_->x = probeRequest_.x;
        probe_->y = probeRequest_.y;
        probe_->status = state_.message;
      }
      probeOf_ = probeRequest_;
      probeTechnique_ = probeOf_.right ? state_.splitTechnique : state_.settings.techniques.front();
    }
    if (!result_ || !probePixel_ || probeJob_.valid()) return;
    const auto [x, y] = *probePixel_;
    if (x >= result_->visibility.width() || y >= result_->visibility.height()) return;
    // Right of the divider the probe is the right side's; the light pass's depth is the same.
    const bool right = splitResult_ && x >= dividerPixel();
    const ProbeRequest wanted{x, y, right, renderGeneration_};
    if (probe_ && probeOf_ == wanted) return;
    tryOrReport([&] {
      readDepthMaps();
      probeRequest_ = wanted;
      probeStarted_ = Clock::now();
      probeFrames_ = 0;
      longestProbeFrameMs_ = 0.0;
      probeJob_ = std::async(std::launch::async,
                             [result = right ? splitResult_ : result_, maps = depthMaps_, x, y] {
                               return probePixel(*result, *maps, x, y);
                             });
    });
  }

  // Scripted runs wait for the probe they were given.
  bool probePending() const {
    if (!result_ || !probePixel_) return false;
    const auto [x, y] = *probePixel_;
    if (x >= result_->visibility.width() || y >= result_->visibility.height()) return false;
    return probeJob_.valid() || !probe_ || probeOf_.generation != renderGeneration_;
  }

  // The scene area at the top left, one texel per pixel (square maps fitted into the frame).
  void drawWindow() {
    int width = 0, height = 0;
    window_.framebufferSize(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glClearColor(0.12f, 0.12f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (texture_.width() > 0) {
      float w = float(texture_.width()), h = float(texture_.height());
      if (state_.view == View::ShadowMap || state_.view == View::Channel) {
        const float side =
            float(std::min(state_.settings.render.width, state_.settings.render.height));
        w = h = side;
      }
      ImDrawList* background = ImGui::GetBackgroundDrawList();
      background->AddImage(ImTextureID(intptr_t(texture_.id())), ImVec2(0, 0), ImVec2(w, h));
      if (splitResult_ && w == float(texture_.width())) {
        // One pixel wide, on the divider's column: either side keeps every other column. The
        // labels sit in the top 20 rows, on dark boxes to read on any image.
        const float x = float(dividerPixel()) + 0.5f;
        // A filled rectangle, not a line: ImGui anti-aliases lines into the next columns.
        background->AddRectFilled(ImVec2(x - 0.5f, 0.0f), ImVec2(x + 0.5f, h),
                                  IM_COL32(255, 160, 0, 255));
        const std::string left(techniqueId(state_.settings.techniques.front()));
        const std::string right(techniqueId(state_.splitTechnique));
        const ImVec2 leftSize = ImGui::CalcTextSize(left.c_str());
        const ImVec2 rightSize = ImGui::CalcTextSize(right.c_str());
        const ImVec2 leftAt(x - 6.0f - leftSize.x, 3.0f), rightAt(x + 6.0f, 3.0f);
        background->AddRectFilled(
            ImVec2(leftAt.x - 3.0f, 1.0f),
            ImVec2(leftAt.x + leftSize.x + 3.0f, leftAt.y + leftSize.y + 2.0f),
            IM_COL32(0, 0, 0, 190));
        background->AddRectFilled(
            ImVec2(rightAt.x - 3.0f, 1.0f),
            ImVec2(rightAt.x + rightSize.x + 3.0f, rightAt.y + rightSize.y + 2.0f),
            IM_COL32(0, 0, 0, 190));
        background->AddText(leftAt, IM_COL32(255, 255, 255, 255), left.c_str());
        background->AddText(rightAt, IM_COL32(255, 255, 255, 255), right.c_str());
      }
    }
    const bool referenceRunning = referenceJob_ && state_.view == View::Error &&
                                  !referenceJob_->complete() && referenceJob_->failure().empty();
    const bool truthRunning = truthJob_ && state_.view == View::TrueError &&
                              !truthJob_->complete() && truthJob_->failure().empty();
    if (referenceRunning || truthRunning) {
      // While the reference or the true shadow computes: its progress at the scene area's
      // bottom left.
      ImDrawList* background = ImGui::GetBackgroundDrawList();
      const char* text =
          referenceRunning ? state_.referenceStatus.c_str() : state_.truthStatus.c_str();
      const ImVec2 size = ImGui::CalcTextSize(text);
      const ImVec2 at(6.0f, float(texture_.height()) - size.y - 6.0f);
      background->AddRectFilled(ImVec2(at.x - 3.0f, at.y - 2.0f),
                                ImVec2(at.x + size.x + 3.0f, at.y + size.y + 2.0f),
                                IM_COL32(0, 0, 0, 190));
      background->AddText(at, IM_COL32(255, 255, 255, 255), text);
    }
    const float below = float(state_.settings.render.height) + 8.0f;
    const float probeWidth = std::min(900.0f, float(width) - kPanelWidth - 8.0f);
    if (probe_ && float(height) - below >= 160.0f && probeWidth >= 300.0f) {
      // In the error-against-the-truth view, the truth at the probe's pixel too.
      std::string truthLine;
      if (state_.view == View::TrueError && truthShown_ && truthJob_ && truthJob_->complete()) {
        const gl::RenderResult& probed = probeOf_.right && splitResult_ ? *splitResult_ : *result_;
        truthLine = describeTrueShadowAt(probed, {truthJob_->trace(), truthJob_->match()},
                                         probe_->x, probe_->y);
      }
      drawCursorProbe(*probe_, probeTechnique_, 0.0f, below, probeWidth,
                      std::min(420.0f, float(height) - below), truthLine);
    }
    window_.drawUi();
  }

  void writeScreenshot(const std::string& path) {
    int width = 0, height = 0;
    const std::vector<uint8_t> pixels = window_.readBackBuffer(width, height);
    writeEncodedColorPng(width, height, pixels, path);
    std::cout << "wrote " << path << " (" << width << "x" << height << ")\n";
  }

  void applyFileChanges(Changes& changes) {
    if (changes.saveSettings) {
      tryOrReport([&] {
        gl::writeSettingsFile(state_.settingsPath, settingsToSave(state_));
        setMessage(state_, "saved " + state_.settingsPath, false);
      });
    }
    if (changes.loadSettings) {
      tryOrReport([&] {
        state_.settings = loadViewerSettings(state_.settingsPath);
        takeSplitSettings(state_);
        changes.scene = true;
        setMessage(state_, "loaded " + state_.settingsPath, false);
      });
    }
  }

  // Returns whether a key holds the camera moving (the loop must not wait for events then).
  bool handleInput(Changes& changes) {
    const ImGuiIO& io = ImGui::GetIO();
    for (int key : window_.takeKeyPresses()) {  // none while a text field has the keyboard
      if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE);
      if (key == GLFW_KEY_H) state_.showPanel = !state_.showPanel;
      // Taken from this frame's back buffer, before the swap.
      if (key == GLFW_KEY_F12) screenshotRequested_ = true;
    }
    bool moving = false;
    if (!io.WantCaptureKeyboard && state_.cameraMode == CameraMode::Fly) {
      // GLFW's key state (held keys send no events), scaled by the frame's time so that the
      // speed is the same at any frame rate: a slow frame (a render) moves further, not slower.
      const auto held = [&](int key) { return glfwGetKey(window_.handle(), key) == GLFW_PRESS; };
      // The first frame of a press: the time since the last frame was spent waiting for it.
      const float seconds =
          flying_ ? std::clamp(io.DeltaTime, 0.0f, kLongestFlyStepSeconds) : 1.0f / 60.0f;
      const float step =
          kFlySpeedRadiiPerSecond * std::max(state_.scene.modelBounds().radius(), 0.1f);
      glm::vec3 direction(0.0f);
      direction.x = float(held(GLFW_KEY_W)) - float(held(GLFW_KEY_S));
      direction.y = float(held(GLFW_KEY_D)) - float(held(GLFW_KEY_A));
      direction.z = float(held(GLFW_KEY_E)) - float(held(GLFW_KEY_Q));
      if (direction != glm::vec3(0.0f)) {
        flyCamera(state_.camera, direction * (step * seconds));
        changes.render = true;
        moving = true;
      }
    }
    flying_ = moving;
    if (io.WantCaptureMouse) return moving;
    const ImVec2 cursor = io.MousePos;
    const bool mapShown = state_.view == View::ShadowMap || state_.view == View::Channel;
    if (!mapShown && cursor.x >= 0.0f && cursor.y >= 0.0f &&
        cursor.x < float(state_.settings.render.width) &&
        cursor.y < float(state_.settings.render.height)) {
      probePixel_ = {int(cursor.x), int(cursor.y)};
    }
    // A drag moves things only when it started over the scene area, and from the frame after the
    // press: the press's own delta may be a jump from anywhere (the pointer entering the window).
    bool dragging[3] = {false, false, false};
    for (int b = 0; b < 3; ++b) {
      if (ImGui::IsMouseClicked(b)) {
        dragStarted_[b] = cursor.x >= 0.0f && cursor.y >= 0.0f &&
                          cursor.x < float(state_.settings.render.width) &&
                          cursor.y < float(state_.settings.render.height);
      } else if (!ImGui::IsMouseDown(b)) {
        dragStarted_[b] = false;
      } else {
        dragging[b] = dragStarted_[b];
      }
    }
    const ImVec2 d = io.MouseDelta;
    const bool moved = d.x != 0.0f || d.y != 0.0f;
    if (state_.split && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
        std::abs(cursor.x - float(dividerPixel())) <= 5.0f &&
        cursor.y < float(state_.settings.render.height)) {
      draggingDivider_ = true;
    }
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) draggingDivider_ = false;
    if (draggingDivider_) {
      state_.divider = std::clamp(cursor.x / float(state_.settings.render.width), 0.0f, 1.0f);
      changes.display = true;
      return true;
    }
    const float radiansPerPixel = 0.01f;
    if (dragging[ImGuiMouseButton_Left] && moved) {
      if (io.KeyShift) {
        moveLight(d.x, d.y);
      } else if (state_.cameraMode == CameraMode::Orbit) {
        orbitCamera(state_.camera, d.x * radiansPerPixel, d.y * radiansPerPixel);
      } else {
        lookAround(state_.camera, d.x * radiansPerPixel, d.y * radiansPerPixel);
      }
      changes.render = true;
    }
    if (state_.cameraMode == CameraMode::Orbit) {
      if (dragging[ImGuiMouseButton_Right] && d.y != 0.0f) {
        dollyCamera(state_.camera, std::exp(0.01f * d.y));
        changes.render = true;
      }
      if (dragging[ImGuiMouseButton_Middle] && moved) {
        panCamera(state_.camera, -0.002f * d.x, 0.002f * d.y);
        changes.render = true;
      }
      if (io.MouseWheel != 0.0f) {
        dollyCamera(state_.camera, std::exp(-0.1f * io.MouseWheel));
        changes.render = true;
      }
    }
    return moving;
  }

  // The first column right of the divider.
  int dividerPixel() const {
    const int width = state_.settings.render.width;
    return std::clamp(int(std::lround(state_.divider * float(width))), 0, width - 1);
  }

  void moveLight(float dx, float dy) {
    Light& light = state_.light;
    if (light.kind == LightKind::Directional) {
      float azimuth = 0.0f, elevation = 0.0f;
      lightAnglesOf(light.direction, azimuth, elevation);
      light.direction =
          lightDirectionFrom(azimuth + 0.5f * dx, std::clamp(elevation - 0.5f * dy, 1.0f, 90.0f));
    } else {
      // Spot: orbit its position about its target; point: about the model's centre (not a sky
      // dome's).
      const glm::vec3 centre =
          light.kind == LightKind::Spot ? light.target : state_.scene.modelBounds().centre();
      Camera around{light.position, centre, light.spotAngleDegrees};
      orbitCamera(around, 0.01f * dx, -0.01f * dy);
      light.position = around.position;
    }
  }

  const ViewerOptions& options_;
  ViewerWindow& window_;
  gl::CurrentContext context_{gl::GlErrors::Report};  // penumbra's own window: its errors are ours
  gl::Renderer renderer_;
  ViewerState state_;
  // Shared with the background jobs (the reference, the probe), which read them as they were.
  std::shared_ptr<const gl::RenderResult> result_;
  std::shared_ptr<const gl::RenderResult> splitResult_;  // the split view's right side
  uint64_t renderGeneration_ = 0;                        // counts renders
  gl::RenderSettings resultSettings_;                    // what result_ was rendered with
  // The error view's filtered reference: the job computing it, the rows shown so far.
  std::unique_ptr<ReferenceJob> referenceJob_;
  std::vector<std::unique_ptr<ReferenceJob>> retiredJobs_;  // stopping; destroyed once finished

  void retireReferenceJob() {
    std::erase_if(retiredJobs_, [](const auto& job) { return job->finished(); });
    if (!referenceJob_) return;
    referenceJob_->stop();
    retiredJobs_.push_back(std::move(referenceJob_));
  }
  std::optional<Image> reference_;
  int referenceRowsShown_ = -1;
  // The error against the true shadow: the loaded scene's BVH (made when the view first needs
  // it), the job tracing the last render's view, the jobs stopping (destroyed once finished).
  gl::FrameView resultView_;  // the camera and light result_ was rendered with
  std::shared_ptr<RaySceneSlot> raySceneSlot_;
  std::unique_ptr<TrueShadowJob> truthJob_;
  std::vector<std::unique_ptr<TrueShadowJob>> retiredTruthJobs_;
  bool truthShown_ = false;      // the scene area shows truthJob_'s complete trace
  bool truthDescribed_ = false;  // and the panel has shown its numbers since the last frame
  int truthFrames_ = 0;          // frames drawn while it traced, and the longest
  double longestTruthFrameMs_ = 0.0;
  Clock::time_point referenceShownAt_;
  std::optional<Clock::time_point> clipClock_;  // when the clip last moved on
  int pendingFrames_ = 0;  // frames drawn while the reference computed, and the longest
  double longestPendingFrameMs_ = 0.0;
  // The last render's light-pass depth per cascade, read when the probe or the reference needs it.
  std::shared_ptr<const std::vector<Image>> depthMaps_;
  std::optional<std::pair<int, int>> probePixel_;
  std::optional<CursorProbe> probe_;
  struct ProbeRequest {
    int x = -1, y = -1;
    bool right = false;       // the split view's right side
    uint64_t generation = 0;  // of the render
    bool operator==(const ProbeRequest&) const = default;
  };
  ProbeRequest probeOf_;       // what probe_ shows
  ProbeRequest probeRequest_;  // what probeJob_ computes
  std::future<CursorProbe> probeJob_;
  Clock::time_point probeStarted_;
  int probeFrames_ = 0;  // frames drawn while probeJob_ ran, and the longest
  double longestProbeFrameMs_ = 0.0;
  Technique probeTechnique_ = Technique::Vsm;  // whose curve the probe draws thick
  bool draggingDivider_ = false;
  bool flying_ = false;                          // a fly key was held last frame
  bool dragStarted_[3] = {false, false, false};  // per mouse button: pressed over the scene area
  SceneTexture texture_;
  int screenshotCount_ = 0;
  bool screenshotRequested_ = false;
};

}  // namespace

gl::Settings loadViewerSettings(const std::string& path) {
  gl::Settings settings;
  // A frame that fits beside the panel in the default window; a file's width and height win.
  settings.render.width = 800;
  settings.render.height = 450;
  if (path.empty()) return settings;
  gl::applySettingsFile(path, settings);
  if (settings.techniques.size() != 1) {
    throw Error(path + ": \"technique\" names " + std::to_string(settings.techniques.size()) +
                " techniques; the viewer shows one at a time");
  }
  checkSceneSource(settings.scene);
  return settings;
}

gl::Settings settingsToSave(const ViewerState& state) {
  gl::Settings s = state.settings;
  SceneOverrides& v = s.view;
  v = {};
  v.cameraPosition = state.camera.position;
  v.cameraTarget = state.camera.target;
  v.cameraFovDegrees = state.camera.verticalFovDegrees;
  v.lightKind = state.light.kind;
  if (state.light.kind == LightKind::Directional) {
    v.lightDirection = state.light.direction;
  } else {
    v.lightPosition = state.light.position;
  }
  if (state.light.kind == LightKind::Spot) {
    v.lightTarget = state.light.target;
    v.spotAngleDegrees = state.light.spotAngleDegrees;
  }
  if (state.light.size > 0.0f) v.lightSize = state.light.size;
  s.split.reset();
  if (state.split) {
    s.split = gl::SplitSettings{state.splitTechnique, state.splitParams, state.divider};
  }
  return s;
}

void takeSplitSettings(ViewerState& state) {
  state.split = state.settings.split.has_value();
  if (state.split) {
    state.splitTechnique = state.settings.split->technique;
    state.splitParams = state.settings.split->params;
    state.divider = state.settings.split->divider;
  }
  state.settings.split.reset();  // the state's fields hold it from here
}

void runViewer(const ViewerOptions& options) {
  // Bad settings are reported before any window opens (and without a display).
  parseView(options.show);
  if (!options.split.empty()) parseTechnique(options.split);
  gl::Settings settings = loadViewerSettings(options.settingsFile);
  if (options.scene) {
    checkSceneSource(*options.scene);
    if (*options.scene != settings.scene) settings.view = {};  // the scene's own view
    settings.scene = *options.scene;
  }
  if (options.ground) settings.ground = *options.ground;
  if (options.casters) settings.casters = *options.casters;
  ViewerWindow window(options.windowWidth, options.windowHeight, "penumbra-viewer");
  Viewer viewer(options, std::move(settings), window);
  viewer.run();
}

}  // namespace penumbra::viewer
