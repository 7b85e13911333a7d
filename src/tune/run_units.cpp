// Running tune's units (tune.h): per scene, the target of every camera-path frame traced once;
// per technique, the search with each point rendered along the path by the one renderer.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

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
// against the shared machine's noise).
constexpr int kSearchTimedFrames = 0;
constexpr int kConfirmTimedFrames = 3;
// How many of the best search points are measured at the user's size before giving up, when
// the better ones exceed the time budget there (they ran at a smaller size in the search).
constexpr int kConfirmCandidates = 5;

// One frame's target and the pixels measured against it.
struct FrameTarget {
  Image visibility;
  Image mask;
};

// The frame size of a search or a confirmation, and its targets.
struct PathTargets {
  int width = 0;
  int height = 0;
  std::vector<FrameTarget> frames;
};

std::string formatNumber(double v) {
  std::ostringstream out;
  out.precision(4);
  out << v;
  return out.str();
}

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
                         const std::vector<Camera>& path, int width, int height) {
  const compare::ComparisonRequest c = comparisonRequestOf(request, width, height);
  const bool areaLight = scene.light.size > 0.0f;
  PathTargets targets{width, height, {}};
  for (size_t f = 0; f < path.size(); ++f) {
    const gl::FrameView view{path[f], scene.light};
    const gl::RenderResult reference = compare::renderReferenceFor(c, renderer, view, areaLight, 1);
    const Image coverage = litSurfaceMask(reference.lookup);
    const gl::RenderResult groundTruth =
        compare::renderReferenceFor(c, renderer, view, areaLight, request.supersample);
    FrameTarget t;
    if (rays) {
      const Image depth = renderer.readCameraDepth();
      compare::TruthResult traced = compare::measureTruth(
          *rays, c, scene, path[f],
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
  }
  return targets;
}

// Squared errors of one frame, plain and leak-weighted, and their pixel count.
struct FrameSums {
  double squared = 0.0;
  double weighted = 0.0;
  long pixels = 0;
  bool finite = true;
};

FrameSums frameSums(const Image& visibility, const FrameTarget& target, double leakWeight) {
  FrameSums s;
  const auto& v = visibility.data();
  const auto& t = target.visibility.data();
  const auto& m = target.mask.data();
  for (size_t i = 0; i < m.size(); ++i) {
    if (!(m[i] > 0.5f)) continue;
    const double e = double(v[i]) - double(t[i]);
    if (!std::isfinite(e)) s.finite = false;
    s.squared += e * e;
    s.weighted += (e > 0.0 ? leakWeight : 1.0) * e * e;  // e > 0: lighter than the target
    ++s.pixels;
  }
  return s;
}

// The measure over frames [first, last) and their RMSE.
struct SetError {
  double measure = 0.0;
  double rmse = 0.0;
};

SetError errorOver(const TuneRequest& request, const std::vector<Image>& visibility,
                   const PathTargets& targets, size_t first, size_t last) {
  double squared = 0.0, weighted = 0.0;
  long pixels = 0;
  for (size_t f = first; f < last; ++f) {
    const FrameSums s = frameSums(visibility[f], targets.frames[f], request.leakWeight);
    squared += s.squared;
    weighted += s.weighted;
    pixels += s.pixels;
  }
  SetError e;
  e.rmse = std::sqrt(squared / double(pixels));
  switch (request.measure) {
    case ErrorMeasure::Rmse: e.measure = e.rmse; break;
    case ErrorMeasure::LeakWeighted: e.measure = std::sqrt(weighted / double(pixels)); break;
    case ErrorMeasure::Flicker: {
      std::vector<Image> truths, masks;
      for (size_t f = first; f < last; ++f) {
        truths.push_back(targets.frames[f].visibility);
        masks.push_back(targets.frames[f].mask);
      }
      const std::span<const Image> estimates(visibility.data() + first, last - first);
      e.measure = e.rmse + temporalFlicker(estimates, truths, masks);
      break;
    }
  }
  return e;
}

// Frame 0 as rendered for the report.
struct FirstFrame {
  Image color;
  Image error;
};

class SceneTuner {
 public:
  SceneTuner(const TuneRequest& request, gl::Renderer& renderer, const std::string& source)
      : request_(request), renderer_(renderer) {
    scene_ = loadScene(source, request.sceneLoad);
    applyOverrides(scene_, request.view);
    requireCascadableLight(request.settings.cascades, scene_.light);
    renderer_.setScene(scene_);
    path_ = scene_.cameraPath(request.frames);
    tuneFrames_ = size_t((request.frames + 1) / 2);
    searchBase_ = request.settings;
    searchBase_.width = std::max(16, int(std::lround(request.settings.width * request.searchScale)));
    searchBase_.height =
        std::max(16, int(std::lround(request.settings.height * request.searchScale)));
    if (request.target == Target::RayTraced) rays_ = std::make_unique<truth::RayScene>(scene_);
    userTargets_ = traceTargets(request, renderer_, rays_.get(), scene_, path_,
                                request.settings.width, request.settings.height);
    if (searchBase_.width == request.settings.width &&
        searchBase_.height == request.settings.height) {
      searchTargets_ = &userTargets_;
    } else {
      ownSearchTargets_ = traceTargets(request, renderer_, rays_.get(), scene_, path_,
                                       searchBase_.width, searchBase_.height);
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
    result.space = requestSpace(request_, unit.technique);
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
    for (size_t k = 0; k < order.size() && k < size_t(kConfirmCandidates); ++k) {
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
      m.status = "over the memory budget: " + formatNumber(double(m.memoryBytes) / kMiB) +
                 " MiB > " + formatNumber(*request_.budgetMib) + " MiB";
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
    for (size_t f = 0; f < path_.size(); ++f) {
      gl::RenderResult r = renderer_.render(settings, gl::FrameView{path_[f], scene_.light});
      const double frameMs = frameTime(r);
      if (f == 0 && !first && slowFrameMs_ && frameMs > *slowFrameMs_) {
        m.tooSlow = true;
        m.status = "too slow to search: its first frame took " + formatNumber(frameMs) +
                   " ms (shader compilation included), over --max-slowdown " +
                   formatNumber(request_.maxSlowdown) + " x the given setting's (limit " +
                   formatNumber(*slowFrameMs_) + " ms)";
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
    for (int k = 0; k < timedFrames; ++k) {
      const gl::RenderResult r = renderer_.render(settings, gl::FrameView{path_[0], scene_.light});
      times.push_back(frameTime(r));
    }
    m.measured = true;
    m.timeMs = median(times);
    const SetError tuning = errorOver(request_, visibility, targets, 0, tuneFrames_);
    const SetError heldOut = errorOver(request_, visibility, targets, tuneFrames_, path_.size());
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
      m.status = "over the time budget: " + formatNumber(m.timeMs) + " ms > " +
                 formatNumber(*request_.budgetMs) + " ms";
      return m;
    }
    m.eligible = true;
    m.status = "ok";
    return m;
  }

  // All passes of a frame: GPU queries where they time execution, else the wall clock.
  double frameTime(const gl::RenderResult& r) const {
    return renderer_.timerQueriesMeasureExecution() ? r.gpuTimes.total() : r.wallTimes.total();
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
              const TuneProgress& progress) {
  validateTuneRequest(request);
  // Each unit: its evaluations and up to 1 + kConfirmCandidates measurements at full size.
  const int total = int(units.size()) * (request.evaluations + 2);
  int done = 0;
  size_t next = 0;
  while (next < units.size()) {
    const std::string& source = units[next].scene;
    if (progress) progress(done, total, "target of " + source);
    SceneTuner tuner(request, renderer, source);
    for (; next < units.size() && units[next].scene == source; ++next) {
      const int unitStart = done;
      UnitResult r = tuner.tune(units[next], [&](const std::string& step) {
        if (progress) progress(std::min(done, unitStart + request.evaluations + 1), total, step);
        ++done;
      });
      done = unitStart + request.evaluations + 2;
      finished(std::move(r));
    }
  }
  if (progress) progress(total, total, "done");
}

}  // namespace penumbra::tune
