// `penumbra tune` (docs/tune.md): for each scene and technique, the setting that minimises the
// error against the truth along the scene's camera path, searched over the registry's own
// parameters (search_space.h, search.h), within time and memory budgets, tuned on some frames
// and reported on held-out ones.
//
// The work is cut into units, one per scene x technique, in a fixed order; a run does all of them
// or, with a shard, every N-th (tune_files.h writes each unit's result; the report is assembled
// from the unit files, so a merged set of shards gives the single run's report).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/area_light.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/truth/true_shadow.h"
#include "penumbra/scene.h"
#include "penumbra/tune/search_space.h"

namespace penumbra::tune {

// What a setting is scored by, on the tuning frames (and reported on the held-out ones).
enum class ErrorMeasure {
  Rmse,          // pooled RMSE of visibility against the target over the frames' pixels
  LeakWeighted,  // the same with each leak's (lighter than the target) square weighted k times
  Flicker,       // RMSE plus the frame-to-frame change beyond the target's own (temporalFlicker)
};
std::string_view errorMeasureName(ErrorMeasure measure);  // "rmse", "leak-weighted", "flicker"
ErrorMeasure parseErrorMeasure(std::string_view name);     // throws Error listing the names

// The target the error is measured against.
enum class Target {
  RayTraced,  // the ray-traced true shadow (penumbra/truth/true_shadow.h) over its pixels
  Filtered,   // the supersampled filtered (or area-light) reference of the user's settings
};
std::string_view targetName(Target target);  // "raytraced", "filtered"
Target parseTarget(std::string_view name);

// A leak's squared error counts this many times under leak-weighted, so a leak costs as much as
// an over-darkening twice its size (docs/tune.md: light through an occluder reads as a defect, a
// shadow a little too dark as a softer shadow — a judgement, not a measurement; --leak-weight).
inline constexpr double kDefaultLeakWeight = 4.0;
// The least first-frame time --max-slowdown refuses a setting at, ms: a first frame compiles its
// shaders (up to a few hundred ms on llvmpipe), which must not refuse a fast setting.
inline constexpr double kMinSlowFrameMs = 1000.0;

struct TuneRequest {
  std::vector<std::string> scenes{"backyard"};  // built-in names or scene files
  SceneLoadOptions sceneLoad;
  SceneOverrides view;
  std::vector<Technique> techniques;
  // The user's setting (compare's defaults unless set): the search's start, its frame size and
  // every fixed setting.
  gl::RenderSettings settings;
  // Only these dimensions are searched (search_space.h restrictedTo); empty: every one.
  std::vector<std::string> only;
  Target target = Target::RayTraced;
  ErrorMeasure measure = ErrorMeasure::Rmse;
  double leakWeight = kDefaultLeakWeight;  // [1, 100]
  std::optional<double> budgetMs;          // warm frame time per setting, > 0
  std::optional<double> budgetMib;         // the up-front memory estimate, > 0
  // Camera-path frames, [2, 32]: the first half (rounded up) tunes, the rest is held out.
  int frames = 4;
  int supersample = 4;           // the target's sub-pixels per side, [1, 8]
  // The ray-traced target's light samples for a light with a size, and the filtered target's
  // area-light samples: compare's defaults.
  int truthLightSamples = truth::kDefaultTrueShadowLightSamples;
  int areaLightSamples = kMinAreaLightSamples;
  double tau = 0.05;             // leak / over-darkening threshold of the reported shares
  int evaluations = 24;          // per unit, the user's setting included, [1, 10000]
  // A setting whose first frame takes longer than this many times the user's setting's warm
  // frame (and at least kMinSlowFrameMs) is not searched further: tuning looks for the best
  // setting near the user's cost (the frontier shows the trade), and on llvmpipe the driver's
  // anisotropic filter takes 12-14 s for a first VSM frame at 2048² where bilinear takes 0.2 s
  // (docs/results/tune-llvmpipe-2026-12-03.md). [1, 1e6].
  double maxSlowdown = 4.0;
  // The search's frame size as a share of the user's, (0, 1]: the winner and the user's setting
  // are measured again at the user's size.
  double searchScale = 1.0;
};

// The camera-path frames that tune, the first ones: half of them, rounded up; the rest are
// held out.
inline int tuningFrames(const TuneRequest& request) { return (request.frames + 1) / 2; }

// Throws Error for a value out of range (stating the range), an unknown scene, or an --only name
// no selected technique's space has (listing theirs).
void validateTuneRequest(const TuneRequest& request);

// The space searched for `technique` under the request (its --only applied) for a scene whose
// light is of kind `light`.
SearchSpace requestSpace(const TuneRequest& request, Technique technique, LightKind light);

// One unit of work: a scene and a technique.
struct WorkUnit {
  int index = 0;  // its place in the fixed order (scenes outer, techniques inner)
  std::string scene;
  Technique technique = Technique::Vsm;
};
std::vector<WorkUnit> workUnits(const TuneRequest& request);
// "K/N" with 1 <= K <= N: the units of shard K (index % N == K - 1). Throws Error otherwise.
struct Shard {
  int index = 1;
  int count = 1;
};
Shard parseShard(std::string_view text);
std::vector<WorkUnit> shardUnits(const std::vector<WorkUnit>& units, const Shard& shard);

// A setting measured over the camera path.
struct Measurement {
  // Eligible: measured, within every budget. Otherwise `status` says why not ("over the time
  // budget: 12.3 ms > 10 ms", the renderer's refusal, ...).
  bool eligible = false;
  std::string status;
  bool measured = false;  // rendered (false: refused before rendering, e.g. over memory)
  bool tooSlow = false;   // refused after its first frame by --max-slowdown
  double tuneError = 0.0;     // the request's measure on the tuning frames
  double heldOutError = 0.0;  // on the held-out frames
  double tuneRmse = 0.0;
  double heldOutRmse = 0.0;
  // Frame 0 against the target over its pixels: with the ray-traced target, what `compare`
  // reports as vs_truth for the same setting.
  double frame0Rmse = 0.0;
  double frame0LeakShare = 0.0;
  double frame0DarkShare = 0.0;
  double timeMs = 0.0;  // warm frame, all passes (GPU queries where they time execution)
  uint64_t memoryBytes = 0;  // estimateMemory at the user's frame size
};

struct Evaluation {
  Point point;
  Measurement measurement;  // at the search's frame size
};

struct UnitResult {
  WorkUnit unit;
  std::string sceneName;  // as loaded
  std::string device;
  SearchSpace space;
  std::vector<Evaluation> evaluations;  // in order; the first is the user's setting
  int best = -1;                        // index into evaluations; -1: none eligible
  int rounds = 0;
  // At the user's frame size: the user's setting and the returned one.
  Measurement defaultAtUserSize;
  std::optional<Measurement> bestAtUserSize;
  // The returned setting in full (the user's, with the best point applied).
  gl::RenderSettings bestSettings;
  // Frame 0 at the user's size, row 0 at the top: colour and visibility - target (0 off the
  // target's pixels) of the user's setting and of the returned one, and the target's own.
  Image defaultColor, defaultError, bestColor, bestError, targetVisibility;
  double seconds = 0.0;  // wall time of the unit, the target's tracing included
};

// step: what is being done; done/total: frames traced and settings measured, so far and in all.
using TuneProgress = std::function<void(int done, int total, const std::string& step)>;

// Runs `units` (all of one request), calling `finished` as each completes (the command writes
// its folder then). Scenes are loaded and their targets traced once for all their techniques;
// `loaded` sees each scene as loaded, before its targets are traced (the command prints its
// warnings and notes).
void runUnits(const TuneRequest& request, const std::vector<WorkUnit>& units,
              gl::Renderer& renderer, const std::function<void(UnitResult)>& finished,
              const TuneProgress& progress = {},
              const std::function<void(const Scene&)>& loaded = {});

}  // namespace penumbra::tune
