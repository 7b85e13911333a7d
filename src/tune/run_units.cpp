// Running tune's units (tune.h): per scene, the target of every camera-path frame traced once;
// per technique, the search with each point rendered along the path by the one renderer.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

#include "path_error.h"
#include "penumbra/area_light.h"
#include "penumbra/compare/comparison.h"
#include "penumbra/compare/truth_measurement.h"
#include "penumbra/error.h"
#include "penumbra/metrics.h"
#include "penumbra/tune/search.h"
#include "penumbra/tune/tune.h"

namespace penumbra::tune {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;
// Warm frames timed per setting: none more during the search, whose time is the path's last
// frame (the frames before it warmed the passes: resources allocated, shaders compiled); three
// when the user's and the returned setting are measured at the user's size (their median,
// against the shared machine's noise), after an untimed one that warms the variant they draw.
constexpr int kSearchTimedFrames = 0;
constexpr int kConfirmTimedFrames = 3;
// How many of the best search points are measured at the user's size before giving up, when
// the better ones exceed the time budget there (they ran at a smaller size in the search).
constexpr int kConfirmCandidates = 5;

// The request as compare's, for the shared reference and truth code.
compare::ComparisonRequest comparisonRequestOf(const TuneRequest& request, int width, int height) {
  compare::ComparisonRequest c;
  c.settings = request.settings;
  c.settings.width = width;
  c.settings.height = height;
  c.supersample = request.supersample;
  c.tau = request.tau;
  c.truthLightSamples = request.truthLightSamples;
  c.areaLightSamples = request.areaLightSamples;
  return c;
}

PathTargets traceTargets(const TuneRequest& request, gl::Renderer& renderer,
                         const truth::RayScene* rays, const Scene& scene,
                         const std::vector<Camera>& path, int width, int height,
                         const std::function<void()>& onFrame) {
  const compare::ComparisonRequest c = comparisonRequestOf(request, width, height);
  const bool areaLight = scene.light.size > 0.0f;
  PathTargets targets{width, height, {}};
  for (size_t f = 0; f < path.size(); ++f) {
    const gl::FrameView view{path[f], scene.light};
    namespace fi = gl::frame_image;
    const gl::RenderResult reference =
        compare::renderReferenceFor(c, renderer, view, areaLight, 1, fi::kVisibility | fi::kLookup);
    const Image coverage = litSurfaceMask(reference.lookup);
    const gl::RenderResult groundTruth = compare::renderReferenceFor(
        c, renderer, view, areaLight, request.supersample, fi::kVisibility);
    FrameTarget t;
    if (rays) {
      const Image depth = renderer.readCameraDepth();
      compare::TruthResult traced =
          compare::measureTruth(*rays, c, scene, path[f],
                                {coverage, depth, reference.visibility, groundTruth.visibility});
      t.visibility = std::move(traced.visibility);
      t.mask = std::move(traced.coverage);
    } else {
      t.visibility = groundTruth.visibility;
      t.mask = coverage;
    }
    if (std::none_of(t.mask.data().begin(), t.mask.data().end(),
                     [](float m) { return m > 0.5f; })) {
      throw Error("scene '" + scene.name + "' frame " + std::to_string(f) +
                  " shows no lit surface to measure inside the shadow map (does the light face "
                  "the view?): nothing to tune against");
    }
    targets.frames.push_back(std::move(t));
    onFrame();
  }
  return targets;
}

// Frame 0 as rendered for the report.
struct FirstFrame {
  Image color;
  Image error;
};

class SceneTuner {
 public:
  // onLoaded: called with the scene as loaded; onFrame: as each frame's target is traced.
  SceneTuner(const TuneRequest& request, gl::Renderer& renderer, const std::string& source,
             const std::function<void(const Scene&)>& onLoaded,
             const std::function<void()>& onFrame)
      : request_(request), renderer_(renderer) {
    SceneLoadOptions load = request.sceneLoad;
    load.aspect = float(request.settings.width) / float(request.settings.height);  // the frame's
    scene_ = loadScene(source, load);
    applyOverrides(scene_, request.view);
    if (onLoaded) onLoaded(scene_);
    requireCascadableLight(request.settings.cascades, scene_.light);
    renderer_.setScene(scene_);
    path_ = scene_.cameraPath(request.frames);
    tuneFrames_ = size_t(tuningFrames(request));
    searchBase_ = request.settings;
    searchBase_.width =
        std::max(16, int(std::lround(request.settings.width * request.searchScale)));
    searchBase_.height =
        std::max(16, int(std::lround(request.settings.height * request.searchScale)));
    if (request.target == Target::RayTraced) rays_ = std::make_unique<truth::RayScene>(scene_);
    userTargets_ = traceTargets(request, renderer_, rays_.get(), scene_, path_,
                                request.settings.width, request.settings.height, onFrame);
    if (searchBase_.width == request.settings.width &&
        searchBase_.height == request.settings.height) {
      searchTargets_ = &userTargets_;
    } else {
      ownSearchTargets_ = traceTargets(request, renderer_, rays_.get(), scene_, path_,
                                       searchBase_.width, searchBase_.height, [] {});
      searchTargets_ = &ownSearchTargets_;
    }
  }

  const Scene& scene() const { return scene_; }

  UnitResult tune(const WorkUnit& unit, const std::function<void(const std::string&)>& step) {
    const auto started = std::chrono::steady_clock::now();
    UnitResult result;
    result.unit = unit;
    result.sceneName = scene_.name;
    result.device = renderer_.deviceDescription();
    gl::RenderSettings user = request_.settings;
    user.technique = unit.technique;
    result.space = requestSpace(request_, unit.technique, scene_.light.kind);
    const SearchSpace& space = result.space;

    slowFrameMs_.reset();  // set by the user's setting, the first evaluation
    const Objective objective = [&](const Point& point) {
      Evaluation e;
      e.point = point;
      step(std::string(techniqueId(unit.technique)) + ", setting " +
           std::to_string(result.evaluations.size() + 1));
      try {
        const gl::RenderSettings s = applyPoint(space, searchBase_, point);
        e.measurement = measure(s, *searchTargets_, kSearchTimedFrames, nullptr);
      } catch (const Error& error) {
        e.measurement.status = error.what();  // a combination the registry refuses
      }
      if (!slowFrameMs_ && e.measurement.measured) {
        slowFrameMs_ = std::max(kMinSlowFrameMs, request_.maxSlowdown * e.measurement.timeMs);
      }
      result.evaluations.push_back(e);
      return Trial{e.measurement.tuneError, e.measurement.eligible, e.measurement.tooSlow};
    };
    SearchLimits limits;
    limits.maxEvaluations = request_.evaluations;
    const SearchResult found = searchBest(space, pointOf(space, user), objective, limits);
    result.rounds = found.rounds;

    // The user's setting and the winner at the user's size; a winner over the time budget
    // there gives way to the next best.
    FirstFrame first;
    step(std::string(techniqueId(unit.technique)) + ", the user's setting at full size");
    result.defaultAtUserSize = measure(user, userTargets_, kConfirmTimedFrames, &first);
    result.defaultColor = first.color;
    result.defaultError = first.error;
    result.targetVisibility = userTargets_.frames.front().visibility;
    std::vector<int> order;
    for (size_t i = 0; i < result.evaluations.size(); ++i) {
      if (result.evaluations[i].measurement.eligible) order.push_back(int(i));
    }
    // Stable: among equal errors the earlier (the user's setting first) wins.
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return result.evaluations[size_t(a)].measurement.tuneError <
             result.evaluations[size_t(b)].measurement.tuneError;
    });
    // The user's setting (evaluation 0) is always among the candidates: if the better ones
    // exceed the time budget at full size, it is what fits.
    if (order.size() > size_t(kConfirmCandidates)) order.resize(size_t(kConfirmCandidates));
    if (std::find(order.begin(), order.end(), 0) == order.end() && !result.evaluations.empty() &&
        result.evaluations[0].measurement.eligible) {
      order.push_back(0);
    }
    for (size_t k = 0; k < order.size(); ++k) {
      const Evaluation& e = result.evaluations[size_t(order[k])];
      const gl::RenderSettings s = applyPoint(space, user, e.point);
      step(std::string(techniqueId(unit.technique)) + ", the best setting at full size");
      Measurement m = measure(s, userTargets_, kConfirmTimedFrames, &first);
      if (!m.eligible) continue;
      result.best = order[k];
      result.bestAtUserSize = m;
      result.bestSettings = s;
      result.bestColor = first.color;
      result.bestError = first.error;
      break;
    }
    // At full size the user's setting may measure better than the search's winner (a search at
    // a smaller --search-scale): then it is the answer, so the tuned setting is never worse.
    if (result.best > 0 && result.defaultAtUserSize.eligible &&
        result.defaultAtUserSize.tuneError <= result.bestAtUserSize->tuneError) {
      result.best = 0;
      result.bestAtUserSize = result.defaultAtUserSize;
      result.bestSettings = applyPoint(space, user, result.evaluations[0].point);
      result.bestColor = result.defaultColor;
      result.bestError = result.defaultError;
    }
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
  }

 private:
  // Renders `settings` along the path and scores it against `targets`.
  Measurement measure(const gl::RenderSettings& settings, const PathTargets& targets,
                      int timedFrames, FirstFrame* first) {
    Measurement m;
    gl::RenderSettings atUserSize = settings;
    atUserSize.width = request_.settings.width;
    atUserSize.height = request_.settings.height;
    m.memoryBytes = gl::estimateMemory(atUserSize, scene_.light.kind).total();
    if (request_.budgetMib && double(m.memoryBytes) / kMiB > *request_.budgetMib) {
      m.status = "over the memory budget";  // memory_bytes says by how much
      return m;
    }
    try {
      renderer_.validate(settings, scene_.light.kind);
      gl::Renderer::checkSoftShadows(settings, scene_.light);
    } catch (const Error& e) {
      m.status = e.what();
      return m;
    }
    std::vector<Image> visibility;
    double lastFrameMs = 0.0;
    namespace fi = gl::frame_image;
    gl::RenderSettings frameSettings = settings;
    for (size_t f = 0; f < path_.size(); ++f) {
      // The visibility is measured; the first frame's colour is shown for the given setting.
      frameSettings.readBack = fi::kVisibility | (f == 0 && first ? fi::kColor : fi::kNone);
      gl::RenderResult r = renderer_.render(frameSettings, gl::FrameView{path_[f], scene_.light});
      const double frameMs = frameTime(r);
      if (f == 0 && !first && slowFrameMs_ && frameMs > *slowFrameMs_) {
        m.tooSlow = true;
        // No measured time in the status: a report compares equal whatever the times.
        m.status =
            "too slow to search: its first frame (shader compilation included) took "
            "longer than --max-slowdown x the given setting's";
        m.timeMs = frameMs;
        return m;
      }
      if (f == 0 && first) {
        first->color = r.color;
        first->error = signedVisibilityError(r.visibility, targets.frames[0].visibility,
                                             targets.frames[0].mask);
      }
      visibility.push_back(std::move(r.visibility));
      lastFrameMs = frameMs;
    }
    std::vector<double> times;
    if (timedFrames == 0) times.push_back(lastFrameMs);
    frameSettings.readBack = fi::kNone;  // timed only: nothing to wait for but the passes
    if (timedFrames > 0) {
      // Untimed first: a frame that reads nothing back draws the camera pass's colour alone, a
      // variant of its own (gl::writesDiagnostics), compiled at its first draw, with targets of
      // its own.
      gl::RenderSettings warmUp = frameSettings;
      warmUp.timing = false;
      renderer_.render(warmUp, gl::FrameView{path_[0], scene_.light});
    }
    for (int k = 0; k < timedFrames; ++k) {
      const gl::RenderResult r =
          renderer_.render(frameSettings, gl::FrameView{path_[0], scene_.light});
      times.push_back(frameTime(r));
    }
    m.measured = true;
    m.timeMs = median(times);
    const SetError tuning =
        errorOver(request_.measure, request_.leakWeight, visibility, targets, 0, tuneFrames_);
    const SetError heldOut = errorOver(request_.measure, request_.leakWeight, visibility, targets,
                                       tuneFrames_, path_.size());
    m.tuneError = tuning.measure;
    m.tuneRmse = tuning.rmse;
    m.heldOutError = heldOut.measure;
    m.heldOutRmse = heldOut.rmse;
    const VisibilityErrors frame0 = measureVisibilityErrors(
        visibility[0], targets.frames[0].visibility, targets.frames[0].mask, request_.tau);
    m.frame0Rmse = frame0.rmse;
    m.frame0LeakShare = frame0.leakShare;
    m.frame0DarkShare = frame0.darkShare;
    if (!std::isfinite(m.tuneError) || !std::isfinite(m.heldOutError)) {
      m.status = "the visibility is not a finite number on some pixel";
      return m;
    }
    if (request_.budgetMs && m.timeMs > *request_.budgetMs) {
      m.status = "over the time budget";  // time_ms says by how much
      return m;
    }
    m.eligible = true;
    m.status = "ok";
    return m;
  }

  // All passes of a frame: GPU queries where they time execution, else the wall clock.
  double frameTime(const gl::RenderResult& r) const {
    return renderer_.timerQueriesMeasureExecution() ? r.gpuTimes.value().total()
                                                    : r.wallTimes.value().total();
  }

  const TuneRequest& request_;
  gl::Renderer& renderer_;
  std::optional<double> slowFrameMs_;  // during a search: --max-slowdown's limit
  Scene scene_;
  std::vector<Camera> path_;
  size_t tuneFrames_ = 1;
  gl::RenderSettings searchBase_;
  std::unique_ptr<truth::RayScene> rays_;
  PathTargets userTargets_;
  PathTargets ownSearchTargets_;
  const PathTargets* searchTargets_ = nullptr;
};

}  // namespace

void runUnits(const TuneRequest& request, const std::vector<WorkUnit>& units,
              gl::Renderer& renderer, const std::function<void(UnitResult)>& finished,
              const TuneProgress& progress, const std::function<void(const Scene&)>& loaded) {
  validateTuneRequest(request);
  // Steps: each scene's frames traced, and each unit's evaluations and the two settings measured
  // at full size (a third or more, when the best exceeds the time budget there, is not counted).
  std::set<std::string> scenes;
  for (const WorkUnit& u : units) scenes.insert(u.scene);
  const int perUnit = request.evaluations + 2;
  const int total = int(scenes.size()) * request.frames + int(units.size()) * perUnit;
  int done = 0;
  size_t next = 0;
  while (next < units.size()) {
    const std::string& source = units[next].scene;
    if (progress) progress(done, total, "the target of " + source);
    SceneTuner tuner(request, renderer, source, loaded, [&] {
      ++done;
      if (progress) progress(done, total, "the target of " + source);
    });
    for (; next < units.size() && units[next].scene == source; ++next) {
      const int unitStart = done;
      UnitResult r = tuner.tune(units[next], [&](const std::string& step) {
        if (progress) progress(std::min(done, unitStart + perUnit - 1), total, step);
        ++done;
      });
      done = unitStart + perUnit;
      finished(std::move(r));
    }
  }
  if (progress) progress(total, total, "done");
}

}  // namespace penumbra::tune
