// penumbra-truth-bench: how fast the ray-traced truth is beside what it replaces as the ground
// truth. Per scene: the BVH build; V_true at compare's defaults (480 x 270, 4 x 4 sub-pixels)
// for the hard light against the GPU filtered reference of the same size and supersampling, and
// for a light with a size (64 samples per sub-pixel) against the 64-shadow-map area-light
// reference; the trace's rays per second beside a bare Embree loop over the same rays.
//
// Usage: penumbra-truth-bench [--repeat N] [--light-size X] [--camera X,Y,Z --target X,Y,Z]
//                             [SCENE...]
// backyard and penumbrae always, then each SCENE (a built-in name or a scene file; --camera and
// --target place the files' camera: a file's default camera frames its bounding sphere, where a
// flat grid fills a tenth of the frame). Every timing is the best of N runs (default 2: the first
// warms caches and compiles shaders).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "bare_embree_rays.h"
#include "penumbra/area_light.h"
#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/render_setting_values.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/truth/true_shadow.h"

namespace penumbra::bench {
namespace {

struct Options {
  int repeat = 2;
  float lightSize = 0.05f;  // a directional light's (tangent of the disk's angular diameter)
  std::vector<std::string> scenes{"backyard", "penumbrae"};
  SceneOverrides fileView;  // camera position and target for scene files
};

glm::vec3 parseVector(const std::string& option, const std::string& text) {
  glm::vec3 v;
  char end = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v.x, &v.y, &v.z, &end) != 3) {
    throw Error(option + " takes X,Y,Z (three numbers, commas, no spaces), not '" + text + "'");
  }
  return v;
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw Error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--repeat") {
      o.repeat = std::stoi(value());
      if (o.repeat < 1 || o.repeat > 10) throw Error("--repeat must be in [1, 10]");
    } else if (arg == "--light-size") {
      o.lightSize = std::stof(value());
    } else if (arg == "--camera") {
      o.fileView.cameraPosition = parseVector(arg, value());
    } else if (arg == "--target") {
      o.fileView.cameraTarget = parseVector(arg, value());
    } else if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: penumbra-truth-bench [--repeat N] [--light-size X] [--camera X,Y,Z "
          "--target X,Y,Z] [SCENE...]\n");
      std::exit(0);
    } else if (!arg.empty() && arg[0] == '-') {
      throw Error("unknown option " + arg +
                  " (--repeat N, --light-size X, --camera X,Y,Z, --target X,Y,Z, scenes)");
    } else {
      o.scenes.push_back(arg);
    }
  }
  validateOverrides(o.fileView);
  return o;
}

double secondsOf(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The best of `repeat` runs of `run`, which returns its own seconds; each run's printed.
double bestOf(int repeat, const char* what, const std::function<double()>& run) {
  double best = std::numeric_limits<double>::infinity();
  std::fprintf(stderr, "  %-34s", what);
  for (int i = 0; i < repeat; ++i) {
    const double s = run();
    std::fprintf(stderr, " %8.3f s", s);
    best = std::min(best, s);
  }
  std::fprintf(stderr, "\n");
  return best;
}

// compare's defaults (tools/cli/compare_command.cpp): 480 x 270, 1024^2 map, 5-tap box blur,
// bilinear lookups.
gl::RenderSettings compareSettings() {
  gl::RenderSettings s;
  s.technique = Technique::Pcf;
  s.shadowMapSize = 1024;
  s.blur = {BlurKernel::Box, gl::blurRadiusOfTaps(5),
            gl::defaultBlurSigma(gl::blurRadiusOfTaps(5))};
  s.filter = FilterMode::Bilinear;
  s.width = 480;
  s.height = 270;
  return s;
}

struct LightRow {
  bool measured = false;
  float size = 0.0f;
  int samples = 1;
  double traceSeconds = 0.0;
  double reference4 = 0.0;  // GPU reference at supersample 4 (compare's ground truth)
  double reference1 = 0.0;  // and at 1
  uint64_t cameraRays = 0, shadowRays = 0;
  double bareRaysPerSecond = 0.0;
  uint64_t bareRays = 0;
  double oursRaysPerSecond() const { return double(cameraRays + shadowRays) / traceSeconds; }
};

struct SceneRow {
  std::string name;
  size_t triangles = 0;
  double loadSeconds = 0.0;
  double raySceneSeconds = 0.0;  // the RayScene constructor: copies and the BVH build
  double bvhSeconds = 0.0;       // rtcCommitScene alone
  LightRow hard, soft;
};

// Traces, renders the GPU reference and casts the bare rays for one light.
LightRow measureLight(const truth::RayScene& rayScene, gl::Renderer& renderer, const Scene& scene,
                      const Light& light, int repeat) {
  LightRow row;
  row.measured = true;
  row.size = light.size;
  const bool soft = light.size > 0.0f;
  row.samples = soft ? truth::kDefaultTrueShadowLightSamples : 1;
  const gl::RenderSettings settings = compareSettings();
  truth::TrueShadowRequest request;
  request.camera = scene.camera;
  request.light = light;
  request.viewBounds = scene.viewBounds();
  request.width = settings.width;
  request.height = settings.height;
  request.supersample = 4;
  request.lightSamples = row.samples;
  request.ambient = settings.ambient;
  truth::TrueShadow trace;
  row.traceSeconds = bestOf(repeat, "V_true (S=4)", [&] {
    trace = truth::traceTrueShadow(rayScene, request);
    return trace.seconds;
  });
  row.cameraRays = trace.cameraRays;
  row.shadowRays = trace.shadowRays;
  const gl::FrameView view{scene.camera, light};
  for (int supersample : {4, 1}) {
    const std::string what = std::string(soft ? "area-light reference" : "filtered reference") +
                             " (S=" + std::to_string(supersample) + ")";
    const double best = bestOf(repeat, what.c_str(), [&] {
      return secondsOf([&] {
        if (soft) {
          renderer.renderAreaLightReference(settings, view, kMinAreaLightSamples, supersample);
        } else {
          renderer.renderReference(settings, view, supersample);
        }
      });
    });
    (supersample == 4 ? row.reference4 : row.reference1) = best;
  }
  // 64 samples per sub-pixel: every fourth row's rays (about 1 GB), the rate being the point.
  const RecordedRays rays = recordTrueShadowRays(rayScene, request, soft ? 4 : 1);
  if (rays.cameraRaysInFrame != trace.cameraRays || rays.shadowRaysInFrame != trace.shadowRays) {
    throw Error("the recorded rays (" + std::to_string(rays.cameraRaysInFrame) + " camera, " +
                std::to_string(rays.shadowRaysInFrame) + " shadow) are not the trace's (" +
                std::to_string(trace.cameraRays) + ", " + std::to_string(trace.shadowRays) +
                "): bare_embree_rays.cpp no longer restates true_shadow.cpp");
  }
  BareTiming bare;
  const double bareSeconds = bestOf(repeat, "bare Embree loop, same rays", [&] {
    bare = castBare(rayScene, rays);
    return bare.seconds;
  });
  row.bareRays = bare.rays;
  row.bareRaysPerSecond = double(bare.rays) / bareSeconds;
  return row;
}

std::string vectorText(glm::vec3 v) {
  char text[64];
  std::snprintf(text, sizeof text, "%g,%g,%g", v.x, v.y, v.z);
  return text;
}

SceneRow measureScene(const std::string& name, gl::Renderer& renderer, const Options& options) {
  SceneRow row;
  std::fprintf(stderr, "%s\n", name.c_str());
  Scene scene;
  row.loadSeconds = secondsOf([&] { scene = loadScene(name); });
  row.name = scene.name;
  const bool builtin = std::find(builtinSceneNames().begin(), builtinSceneNames().end(), name) !=
                       builtinSceneNames().end();
  if (!builtin && !options.fileView.empty()) {
    applyOverrides(scene, options.fileView);
    const glm::vec3 p = scene.camera.position, t = scene.camera.target;
    row.name += " (camera " + vectorText(p) + " to " + vectorText(t) + ")";
  }
  std::unique_ptr<truth::RayScene> rayScene;
  row.raySceneSeconds = secondsOf([&] { rayScene = std::make_unique<truth::RayScene>(scene); });
  row.triangles = rayScene->triangleCount();
  row.bvhSeconds = rayScene->buildSeconds();
  std::fprintf(stderr, "  %zu triangles, load %.3f s, RayScene %.3f s (BVH %.3f s)\n",
               row.triangles, row.loadSeconds, row.raySceneSeconds, row.bvhSeconds);
  renderer.setScene(scene);
  Light hard = scene.light;
  hard.size = 0.0f;
  row.hard = measureLight(*rayScene, renderer, scene, hard, options.repeat);
  if (scene.light.kind != LightKind::Point) {  // the renderer has no sphere-light reference
    Light soft = scene.light;
    if (!(soft.size > 0.0f)) soft.size = options.lightSize;
    checkLightSize(soft);
    row.soft = measureLight(*rayScene, renderer, scene, soft, options.repeat);
  }
  return row;
}

const char* verdict(double ours, double goal) {
  return ours <= goal ? "yes" : "**no**";
}

void printTables(const std::vector<SceneRow>& rows) {
  std::printf("\n| scene | triangles | load (s) | RayScene (s) | BVH build (s) |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: |\n");
  for (const SceneRow& r : rows) {
    std::printf("| %s | %zu | %.3f | %.3f | %.3f |\n", r.name.c_str(), r.triangles, r.loadSeconds,
                r.raySceneSeconds, r.bvhSeconds);
  }
  std::printf(
      "\n| scene | light | V_true S=4 (s) | GPU reference S=4 (s) | GPU reference S=1 (s) "
      "| V_true <= reference S=4 |\n");
  std::printf("| --- | --- | ---: | ---: | ---: | --- |\n");
  for (const SceneRow& r : rows) {
    for (const LightRow* l : {&r.hard, &r.soft}) {
      if (!l->measured) continue;
      const std::string light = l->size > 0.0f ? "size " + std::to_string(l->size).substr(0, 5) +
                                                     ", " + std::to_string(l->samples) +
                                                     " samples (area ref. 64 maps)"
                                               : std::string("hard (filtered ref.)");
      std::printf("| %s | %s | %.3f | %.3f | %.3f | %s |\n", r.name.c_str(), light.c_str(),
                  l->traceSeconds, l->reference4, l->reference1,
                  verdict(l->traceSeconds, l->reference4));
    }
  }
  std::printf(
      "\n| scene | light | camera rays | shadow rays | V_true (Mrays/s) | bare Embree "
      "(Mrays/s, rays cast) | V_true / bare |\n");
  std::printf("| --- | --- | ---: | ---: | ---: | ---: | ---: |\n");
  for (const SceneRow& r : rows) {
    for (const LightRow* l : {&r.hard, &r.soft}) {
      if (!l->measured) continue;
      std::printf("| %s | %s | %llu | %llu | %.2f | %.2f (%llu) | %.2f |\n", r.name.c_str(),
                  l->size > 0.0f ? "soft" : "hard", (unsigned long long)l->cameraRays,
                  (unsigned long long)l->shadowRays, 1e-6 * l->oursRaysPerSecond(),
                  1e-6 * l->bareRaysPerSecond, (unsigned long long)l->bareRays,
                  l->oursRaysPerSecond() / l->bareRaysPerSecond);
    }
  }
}

int run(int argc, char** argv) {
  const Options options = parseOptions(argc, argv);
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  std::printf("device: %s\nray tracer: %s, %u hardware threads\nrepeat: best of %d\n",
              renderer.deviceDescription().c_str(), truth::embreeDescription().c_str(),
              std::thread::hardware_concurrency(), options.repeat);
  std::vector<SceneRow> rows;
  for (const std::string& name : options.scenes) {
    rows.push_back(measureScene(name, renderer, options));
  }
  printTables(rows);
  return 0;
}

}  // namespace
}  // namespace penumbra::bench

int main(int argc, char** argv) {
  try {
    return penumbra::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "penumbra-truth-bench: %s\n", e.what());
    return 1;
  }
}
