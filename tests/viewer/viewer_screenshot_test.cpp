// penumbra-viewer runs scripted under Xvfb: for every built-in scene its screenshot's scene area
// (the window's top-left frame-sized rectangle) equals `penumbra render` of the same settings
// file, and the settings panel draws (a screenshot with it differs from one without it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include <regex>

#include "../scene/scene_fixtures.h"
#include "display_image.h"  // the viewer's colours for pixels it does not measure
#include "penumbra/diagnostic_images.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/settings_json.h"
#include "penumbra/image_io.h"
#include "penumbra/metrics.h"
#include "penumbra/run_program.h"
#include "penumbra/scene.h"
#include "penumbra/technique.h"
#include "penumbra/truth/true_shadow.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

constexpr int kFrameWidth = 160;
constexpr int kFrameHeight = 90;

RunResult runProgramOnce(const std::vector<std::string>& args, const fs::path& cwd);

// Runs `args` (args[0] found on PATH) in `cwd`, stdout and stderr together. xvfb-run itself
// sometimes fails to remove its temporary folder when several run at once (ctest -j2), which
// changes the exit status and adds a line the program did not write: such a run is repeated once.
RunResult runProgram(const std::vector<std::string>& args, const fs::path& cwd) {
  RunResult result = runProgramOnce(args, cwd);
  if (result.output.find("xvfb-run: error: problem while cleaning up temporary directory") !=
      std::string::npos) {
    result = runProgramOnce(args, cwd);
  }
  return result;
}

RunResult runProgramOnce(const std::vector<std::string>& args, const fs::path& cwd) {
  std::vector<std::string> all = args;
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const fs::path log = cwd / ".viewer-test-output";
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || dup2(fd, 1) < 0 || dup2(fd, 2) < 0 || chdir(cwd.c_str()) != 0) _exit(127);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  RunResult result;
  waitpid(pid, &result.status, 0);
  result.output = readFile(log);
  fs::remove(log);
  return result;
}

bool haveXvfbRun() {
  return penumbra::runProgram({"xvfb-run", "--help"}).started;
}

// CI must run these tests; elsewhere they skip without xvfb-run (Debian's xvfb).
#define REQUIRE_XVFB()                                                                       \
  do {                                                                                       \
    if (!haveXvfbRun()) {                                                                    \
      const char* ci = std::getenv("CI");                                                    \
      if (ci != nullptr && std::string(ci) == "true") FAIL() << "xvfb-run is not installed"; \
      GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs xvfb)";      \
    }                                                                                        \
  } while (false)

// The viewer scripted for three frames in a 1280x800 Xvfb screen, its window's PNG at `png`.
RunResult runViewer(const fs::path& settings, const fs::path& png, const fs::path& cwd,
                    const std::vector<std::string>& options = {}) {
  std::vector<std::string> args{"xvfb-run", "-a", "-s", "-screen 0 1280x800x24",
                                PENUMBRA_VIEWER_EXECUTABLE};
  for (const std::string& a :
       {std::string("--settings"), settings.string(), std::string("--frames"), std::string("3"),
        std::string("--screenshot"), png.string()}) {
    args.push_back(a);
  }
  args.insert(args.end(), options.begin(), options.end());
  return runProgram(args, cwd);
}

fs::path writeSettings(const fs::path& folder, const std::string& scene, Technique technique) {
  std::ostringstream json;
  json << "{\"scene\": \"" << scene << "\", \"technique\": \"" << techniqueId(technique)
       << "\", \"shadow-size\": 256, \"blur\": 3, \"filter\": \"bilinear\", \"width\": "
       << kFrameWidth << ", \"height\": " << kFrameHeight << "}\n";
  const fs::path path = folder / (scene + ".json");
  writeFile(path, json.str());
  return path;
}

struct Difference {
  int maxSteps = 0;        // largest difference of one channel, in 8-bit steps
  double meanSteps = 0.0;  // mean absolute difference per channel, in 8-bit steps
};

// The window screenshot's top-left width x height rectangle (the scene area) against `other`'s.
Difference sceneAreaDifference(const Image& window, const Image& other, int width, int height) {
  Difference d;
  double sum = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int steps =
            int(std::lround(std::abs(window.at(x, y, c) - other.at(x, y, c)) * 255.0f));
        d.maxSteps = std::max(d.maxSteps, steps);
        sum += steps;
      }
    }
  }
  d.meanSteps = sum / (3.0 * width * height);
  return d;
}

// Both run on the same driver in CI (Mesa's llvmpipe through EGL and through GLX) and the viewer
// draws the render's sRGB bytes one texel per pixel, so they match exactly there. The tolerance
// leaves room for a machine whose EGL finds a GPU while Xvfb's GLX is llvmpipe: rasterisation and
// float rounding may then move single shadow-edge pixels, not the picture.
constexpr double kMeanStepsTolerance = 0.5;

TEST(Viewer, ScreenshotOfEachSceneEqualsTheHeadlessRender) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const auto techniques = allTechniques();
  size_t i = 0;
  for (std::string_view name : builtinSceneNames()) {
    const std::string scene(name);
    // A different technique on each scene, so that the run covers several.
    const Technique technique = techniques[i++ % techniques.size()];
    SCOPED_TRACE(scene + " with " + std::string(techniqueId(technique)));
    const fs::path settings = writeSettings(scratch.path(), scene, technique);
    const fs::path out = scratch.path() / scene;
    const RunResult render = runPenumbra(
        {"render", "--settings", settings.string(), "--out", out.string()}, scratch.path());
    ASSERT_EQ(render.exitCode(), 0) << render.output;
    const fs::path shot = scratch.path() / (scene + "_viewer.png");
    const RunResult viewer = runViewer(settings, shot, scratch.path());
    ASSERT_EQ(viewer.exitCode(), 0) << viewer.output;
    const Image window = readEncodedColorPng(shot);
    const Image headless =
        readEncodedColorPng(out / (scene + "_" + std::string(techniqueId(technique)) + ".png"));
    ASSERT_EQ(headless.width(), kFrameWidth);
    ASSERT_GE(window.width(), kFrameWidth);
    ASSERT_GE(window.height(), kFrameHeight);
    const Difference d = sceneAreaDifference(window, headless, kFrameWidth, kFrameHeight);
    std::cout << scene << " (" << techniqueId(technique) << "): mean difference " << d.meanSteps
              << " steps, largest " << d.maxSteps << "\n";
    EXPECT_LE(d.meanSteps, kMeanStepsTolerance) << "largest channel difference " << d.maxSteps;
  }
}

// A scene file's animation plays as render --frames plays it: the viewer's 31st scripted frame
// is render's frame 30 (the clip at 1 s), pixel for pixel, and differs from its first. --scene,
// --ground and --casters replace the settings file's.
TEST(Viewer, PlaysASceneFilesAnimationAsRenderFramesDo) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const fs::path settings = scratch.path() / "bars.json";
  writeFile(settings,
            "{\"scene\": \"backyard\", \"technique\": \"pcf\", \"shadow-size\": 256, "
            "\"blur\": 3, \"filter\": \"bilinear\", \"width\": " +
                std::to_string(kFrameWidth) + ", \"height\": " + std::to_string(kFrameHeight) +
                ", \"ground\": \"on\"}\n");
  const std::string bars = PENUMBRA_SOURCE_DIR "/tests/data/waving_bars.gltf";
  const fs::path out = scratch.path() / "render";
  const RunResult render = runPenumbra({"render", "--settings", settings.string(), "--scene", bars,
                                        "--ground", "off", "--frames", "31", "--out", out.string()},
                                       scratch.path());
  ASSERT_EQ(render.exitCode(), 0) << render.output;
  const fs::path shot = scratch.path() / "bars_viewer.png";
  std::vector<std::string> args{"xvfb-run",
                                "-a",
                                "-s",
                                "-screen 0 1280x800x24",
                                PENUMBRA_VIEWER_EXECUTABLE,
                                "--settings",
                                settings.string(),
                                "--scene",
                                bars,
                                "--ground",
                                "off",
                                "--frames",
                                "31",
                                "--screenshot",
                                shot.string(),
                                "--hide-panel"};
  const RunResult viewer = runProgram(args, scratch.path());
  ASSERT_EQ(viewer.exitCode(), 0) << viewer.output;
  const Image window = readEncodedColorPng(shot);
  const Image last = readEncodedColorPng(out / "frames" / "waving_bars_pcf_0030.png");
  const Image first = readEncodedColorPng(out / "frames" / "waving_bars_pcf_0000.png");
  EXPECT_LE(sceneAreaDifference(window, last, kFrameWidth, kFrameHeight).meanSteps,
            kMeanStepsTolerance);
  // The bars bend by up to 44 degrees between the two: the frame changes visibly.
  EXPECT_GT(sceneAreaDifference(window, first, kFrameWidth, kFrameHeight).meanSteps, 1.0);
}

TEST(Viewer, ThePanelDrawsBesideTheSceneArea) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const fs::path settings = writeSettings(scratch.path(), "bench", Technique::Vsm);
  const fs::path withPanel = scratch.path() / "with_panel.png";
  const fs::path withoutPanel = scratch.path() / "without_panel.png";
  const RunResult shown = runViewer(settings, withPanel, scratch.path());
  ASSERT_EQ(shown.exitCode(), 0) << shown.output;
  const RunResult hidden = runViewer(settings, withoutPanel, scratch.path(), {"--hide-panel"});
  ASSERT_EQ(hidden.exitCode(), 0) << hidden.output;
  const Image a = readEncodedColorPng(withPanel);
  const Image b = readEncodedColorPng(withoutPanel);
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  // The panel covers the window's right edge, full height: most of a column there changes.
  int differing = 0;
  for (int y = 0; y < a.height(); ++y) {
    const int x = a.width() - 100;
    differing += a.at(x, y, 0) != b.at(x, y, 0) || a.at(x, y, 1) != b.at(x, y, 1) ||
                 a.at(x, y, 2) != b.at(x, y, 2);
  }
  EXPECT_GT(differing, a.height() / 4) << "the panel did not draw";
  // The scene area is the same with and without it.
  EXPECT_EQ(sceneAreaDifference(a, b, kFrameWidth, kFrameHeight).maxSteps, 0);
}

// Pixels of the window's rectangle [x0, x1) x [y0, y1) that differ between two screenshots.
// A scripted run's report of a background job ("cursor probe", "filtered reference"): its time,
// the frames the window drew meanwhile and the longest of them.
struct BackgroundTiming {
  double jobMs = 0.0;
  int frames = 0;
  double longestMs = 0.0;
};

BackgroundTiming backgroundTiming(const std::string& output, const std::string& job) {
  const std::regex line(job + R"(: ([0-9.]+) ms on a background thread; ([0-9]+) frames drawn )"
                              R"(meanwhile, the longest ([0-9.]+) ms)");
  std::smatch m;
  if (!std::regex_search(output, m, line)) {
    ADD_FAILURE() << "no '" << job << "' report in:\n" << output;
    return {};
  }
  const BackgroundTiming t{std::stod(m[1]), std::stoi(m[2]), std::stod(m[3])};
  std::cout << job << " " << t.jobMs << " ms, " << t.frames << " frames meanwhile, longest "
            << t.longestMs << " ms\n";
  return t;
}

int differingPixels(const Image& a, const Image& b, int x0, int y0, int x1, int y1) {
  int count = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      count += a.at(x, y, 0) != b.at(x, y, 0) || a.at(x, y, 1) != b.at(x, y, 1) ||
               a.at(x, y, 2) != b.at(x, y, 2);
    }
  }
  return count;
}

TEST(Viewer, EveryViewShowsSomethingOtherThanTheShadedFrame) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  // ESM with the Z-max classifier fails somewhere on the backyard's fence; its failure mask, the
  // error against the reference and the channel all differ from the shaded picture.
  const fs::path settings = scratch.path() / "esm.json";
  writeFile(settings,
            "{\"scene\": \"backyard\", \"technique\": \"esm\", \"param\": {\"esm\": "
            "{\"classifier\": \"zmax\"}}, \"shadow-size\": 256, \"blur\": 3, \"width\": " +
                std::to_string(kFrameWidth) + ", \"height\": " + std::to_string(kFrameHeight) +
                "}\n");
  const fs::path shadedPng = scratch.path() / "shaded.png";
  ASSERT_EQ(runViewer(settings, shadedPng, scratch.path(), {"--hide-panel"}).exitCode(), 0);
  const Image shaded = readEncodedColorPng(shadedPng);
  for (const char* view : {"visibility", "error", "failures", "shadowmap", "channel"}) {
    SCOPED_TRACE(view);
    const fs::path png = scratch.path() / (std::string(view) + ".png");
    const RunResult run =
        runViewer(settings, png, scratch.path(), {"--hide-panel", "--show", view});
    ASSERT_EQ(run.exitCode(), 0) << run.output;
    const Image shown = readEncodedColorPng(png);
    EXPECT_GT(differingPixels(shaded, shown, 0, 0, kFrameWidth, kFrameHeight),
              kFrameWidth * kFrameHeight / 10);
  }
}

TEST(Viewer, TheCursorProbeDrawsTheShadowTestCurvesBelowTheSceneArea) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  // A wide filter region (a 15-tap blur under trilinear filtering of a 1024² map): hundreds of
  // taps, a probe that takes a while.
  const fs::path settings = scratch.path() / "planar.json";
  writeFile(settings,
            "{\"scene\": \"planar\", \"technique\": \"vsm\", \"shadow-size\": 1024, "
            "\"blur\": 15, \"filter\": \"trilinear\", \"width\": " +
                std::to_string(kFrameWidth) + ", \"height\": " + std::to_string(kFrameHeight) +
                "}\n");
  const fs::path without = scratch.path() / "without.png";
  const fs::path with = scratch.path() / "with.png";
  ASSERT_EQ(runViewer(settings, without, scratch.path()).exitCode(), 0);
  // The frame's centre: the planar scene's lit ground.
  const RunResult run = runViewer(
      settings, with, scratch.path(),
      {"--probe", std::to_string(kFrameWidth / 2) + "," + std::to_string(kFrameHeight / 2)});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const Image a = readEncodedColorPng(without);
  const Image b = readEncodedColorPng(with);
  // The probe window (about 800 x 400 pixels) below the scene area.
  EXPECT_GT(differingPixels(a, b, 0, kFrameHeight + 10, 700, kFrameHeight + 300), 100000);
  EXPECT_EQ(differingPixels(a, b, 0, 0, kFrameWidth, kFrameHeight), 0);
  // The curves are computed on a background thread: the window kept drawing meanwhile (a probe
  // computed in the frame would draw none), each frame a small part of the probe's time.
  const BackgroundTiming probe = backgroundTiming(run.output, "cursor probe");
  EXPECT_GE(probe.frames, 3);
  EXPECT_LT(probe.longestMs, probe.jobMs / 3.0);
}

TEST(Viewer, SavesSettingsThatPenumbraRenderTurnsIntoTheSamePicture) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const fs::path settings = writeSettings(scratch.path(), "contact", Technique::Msm);
  const fs::path shot = scratch.path() / "viewer.png";
  const fs::path saved = scratch.path() / "saved.json";
  const RunResult run =
      runViewer(settings, shot, scratch.path(), {"--save-settings", saved.string()});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const std::string json = readFile(saved);
  // Everything, the camera and light as the window had them included.
  for (const char* key : {"\"camera\"", "\"light\"", "\"param\"", "\"msm\"", "\"cascades\""}) {
    EXPECT_NE(json.find(key), std::string::npos) << key << " missing from\n" << json;
  }
  const fs::path out = scratch.path() / "render";
  const RunResult render =
      runPenumbra({"render", "--settings", saved.string(), "--out", out.string()}, scratch.path());
  ASSERT_EQ(render.exitCode(), 0) << render.output;
  const Image headless = readEncodedColorPng(out / "contact_msm.png");
  const Difference d =
      sceneAreaDifference(readEncodedColorPng(shot), headless, kFrameWidth, kFrameHeight);
  std::cout << "saved settings: mean difference " << d.meanSteps << " steps, largest " << d.maxSteps
            << "\n";
  // Not byte for byte: a saved light direction is normalised again when it is loaded
  // (applyOverrides), which may move it by a float ulp and a shadow-edge pixel by one step.
  EXPECT_LE(d.meanSteps, kMeanStepsTolerance);
  EXPECT_LE(d.maxSteps, 2);
}

// `penumbra tune`'s best setting loads in the viewer as it renders headless, and the viewer's
// true-shadow error view shows where the tuned setting still fails.
TEST(Viewer, LoadsATunedSettingAndShowsWhereItStillFails) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const RunResult tuned = runPenumbra({"tune",
                                       "--scene",
                                       "contact",
                                       "--technique",
                                       "vsm",
                                       "--evaluations",
                                       "5",
                                       "--width",
                                       std::to_string(kFrameWidth),
                                       "--height",
                                       std::to_string(kFrameHeight),
                                       "--shadow-size",
                                       "256",
                                       "--frames",
                                       "2",
                                       "--supersample",
                                       "1",
                                       "-q",
                                       "--out",
                                       "tuned"},
                                      scratch.path());
  ASSERT_EQ(tuned.exitCode(), 0) << tuned.output;
  const fs::path best = scratch.path() / "tuned" / "best" / "vsm.json";
  ASSERT_TRUE(fs::exists(best));
  // The tuned setting is not the given one, so loading it is more than loading the defaults.
  const std::string tuneJson = readFile(scratch.path() / "tuned" / "tune.json");
  ASSERT_EQ(tuneJson.find("\"best\": 0,"), std::string::npos) << "the search kept the default";
  const fs::path shot = scratch.path() / "viewer.png";
  const RunResult run = runViewer(best, shot, scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const RunResult render =
      runPenumbra({"render", "--settings", best.string(), "--out", "render"}, scratch.path());
  ASSERT_EQ(render.exitCode(), 0) << render.output;
  const Difference d = sceneAreaDifference(
      readEncodedColorPng(shot), readEncodedColorPng(scratch.path() / "render" / "contact_vsm.png"),
      kFrameWidth, kFrameHeight);
  EXPECT_LE(d.meanSteps, kMeanStepsTolerance);

  const fs::path errorShot = scratch.path() / "error.png";
  const RunResult error =
      runViewer(best, errorShot, scratch.path(), {"--show", "truth-error", "--hide-panel"});
  ASSERT_EQ(error.exitCode(), 0) << error.output;
  // The tuned VSM still errs by 0.1 or more somewhere, and the view shows where in the heat
  // map's colours.
  const Image window = readEncodedColorPng(errorShot);
  // The heat map's colours of errors of 0.1 visibility or more, either sign (0.01 apart).
  std::vector<glm::vec3> errorColours;
  for (int k = 10; k <= 50; ++k) {
    for (float sign : {-1.0f, 1.0f}) {
      errorColours.push_back(errorHeatColour(sign * 0.01f * k, viewer::kErrorRange) * 255.0f);
    }
  }
  int erring = 0;
  for (int y = 0; y < kFrameHeight; ++y) {
    for (int x = 0; x < kFrameWidth; ++x) {
      const glm::vec3 bytes(window.at(x, y, 0) * 255.0f, window.at(x, y, 1) * 255.0f,
                            window.at(x, y, 2) * 255.0f);
      for (const glm::vec3& c : errorColours) {
        if (glm::length(bytes - c) < 3.0f) {  // an 8-bit rounding of a palette colour
          ++erring;
          break;
        }
      }
    }
  }
  EXPECT_GT(erring, 0);
}

bool haveXdotool() {
  return penumbra::runProgram({"xdotool", "version"}).started;
}

// The viewer run interactively (no --frames) under Xvfb, driven by xdotool as a user would: F12
// screenshots between a left drag (orbit), a shift drag (the light), a pointer move (the probe)
// and H (the panel), then Esc quits. Waits are generous: llvmpipe compiles shaders at start.
TEST(Viewer, TakesMouseAndKeyboardInput) {
  REQUIRE_XVFB();
  if (!haveXdotool()) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true") FAIL() << "xdotool is not installed";
    GTEST_SKIP() << "xdotool is not installed (scripts/install-deps installs it)";
  }
  ScratchFolder scratch;
  const fs::path settings = writeSettings(scratch.path(), "backyard", Technique::Vsm);
  const fs::path script = scratch.path() / "drive.sh";
  writeFile(script, std::string("#!/bin/bash\n") + PENUMBRA_VIEWER_EXECUTABLE + " --settings " +
                        settings.string() + " > viewer.log 2>&1 &\n" +
                        R"(pid=$!
sleep 8
xdotool key F12; sleep 2
xdotool mousemove 40 40 mousedown 1; sleep 0.3; xdotool mousemove 80 50; sleep 0.3
xdotool mousemove 120 60; sleep 0.5; xdotool mouseup 1; sleep 2
xdotool key F12; sleep 2
xdotool keydown shift mousemove 40 40 mousedown 1; sleep 0.3; xdotool mousemove 80 40; sleep 0.3
xdotool mousemove 120 40; sleep 0.5; xdotool mouseup 1 keyup shift; sleep 2
xdotool key F12; sleep 2
xdotool key h; sleep 1; xdotool key F12; sleep 2
xdotool key Escape
for i in $(seq 1 20); do kill -0 $pid 2> /dev/null || break; sleep 0.5; done
if kill -0 $pid 2> /dev/null; then kill $pid; echo "Esc did not quit"; exit 1; fi
wait $pid
)");
  const RunResult run = runProgram(
      {"xvfb-run", "-a", "-s", "-screen 0 1280x800x24", "bash", script.string()}, scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output << readFile(scratch.path() / "viewer.log");
  std::vector<Image> shots;
  for (int i = 0; i < 4; ++i) {
    const fs::path png = scratch.path() / ("penumbra-viewer-000" + std::to_string(i) + ".png");
    ASSERT_TRUE(fs::exists(png)) << png << " missing (F12 lost?)\n"
                                 << readFile(scratch.path() / "viewer.log");
    shots.push_back(readEncodedColorPng(png));
  }
  const int area = kFrameWidth * kFrameHeight;
  // The orbit moved the camera, the shift drag the light: each changed the picture.
  EXPECT_GT(differingPixels(shots[0], shots[1], 0, 0, kFrameWidth, kFrameHeight), area / 4);
  EXPECT_GT(differingPixels(shots[1], shots[2], 0, 0, kFrameWidth, kFrameHeight), area / 50);
  // The pointer over the scene area opened the probe below it; H hid the panel.
  EXPECT_GT(differingPixels(shots[1], shots[2], 0, kFrameHeight + 10, 700, kFrameHeight + 300),
            10000);
  EXPECT_GT(differingPixels(shots[2], shots[3], 1180, 0, 1181, 800), 200);
}

// Fly mode: holding W moves the camera forward (GLFW's key state: a held key sends no events),
// holding S brings it back. F12 screenshots before, after W and after S.
TEST(Viewer, FlyModeKeysMoveTheCamera) {
  REQUIRE_XVFB();
  if (!haveXdotool()) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true") FAIL() << "xdotool is not installed";
    GTEST_SKIP() << "xdotool is not installed (scripts/install-deps installs it)";
  }
  ScratchFolder scratch;
  const fs::path settings = writeSettings(scratch.path(), "backyard", Technique::Vsm);
  const fs::path script = scratch.path() / "drive.sh";
  writeFile(script, std::string("#!/bin/bash\n") + PENUMBRA_VIEWER_EXECUTABLE +
                        " --fly --settings " + settings.string() + " > viewer.log 2>&1 &\n" +
                        R"(pid=$!
sleep 6
xdotool mousemove 1000 700; sleep 0.5
xdotool key F12; sleep 1
xdotool keydown w; sleep 1; xdotool keyup w; sleep 1.5
xdotool key F12; sleep 1
xdotool keydown s; sleep 1; xdotool keyup s; sleep 1.5
xdotool key F12; sleep 1
xdotool key Escape
for i in $(seq 1 20); do kill -0 $pid 2> /dev/null || break; sleep 0.5; done
if kill -0 $pid 2> /dev/null; then kill $pid; echo "Esc did not quit"; exit 1; fi
wait $pid
)");
  const RunResult run = runProgram(
      {"xvfb-run", "-a", "-s", "-screen 0 1280x800x24", "bash", script.string()}, scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output << readFile(scratch.path() / "viewer.log");
  std::vector<Image> shots;
  for (int i = 0; i < 3; ++i) {
    const fs::path png = scratch.path() / ("penumbra-viewer-000" + std::to_string(i) + ".png");
    ASSERT_TRUE(fs::exists(png)) << png << " missing\n" << readFile(scratch.path() / "viewer.log");
    shots.push_back(readEncodedColorPng(png));
  }
  const int area = kFrameWidth * kFrameHeight;
  const int forward = differingPixels(shots[0], shots[1], 0, 0, kFrameWidth, kFrameHeight);
  const int back = differingPixels(shots[0], shots[2], 0, 0, kFrameWidth, kFrameHeight);
  std::cout << "W changed " << forward << " pixels, W then S left " << back << " changed\n";
  // A second of W moves half the scene's radius: most of the picture changes.
  EXPECT_GT(forward, area / 4);
  // As long a hold of S comes most of the way back (frame times differ, so not exactly).
  EXPECT_LT(back, forward);
}

TEST(Viewer, TheSplitViewShowsEachTechniqueOnItsSideOfTheDivider) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const fs::path settings = writeSettings(scratch.path(), "backyard", Technique::Vsm);
  const fs::path shot = scratch.path() / "split.png";
  const RunResult run = runViewer(settings, shot, scratch.path(), {"--split", "pcf"});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const auto render = [&](const char* technique) {
    const fs::path out = scratch.path() / technique;
    const RunResult r = runPenumbra({"render", "--settings", settings.string(), "--technique",
                                     technique, "--out", out.string()},
                                    scratch.path());
    EXPECT_EQ(r.exitCode(), 0) << r.output;
    return readEncodedColorPng(out / ("backyard_" + std::string(technique) + ".png"));
  };
  const Image window = readEncodedColorPng(shot);
  const Image vsm = render("vsm");
  const Image pcf = render("pcf");
  // The divider starts at half the width; its line covers that column and the technique labels
  // the top 20 rows.
  const int divider = kFrameWidth / 2;
  const int labelRows = 20;
  int leftMismatch = 0, rightMismatch = 0, differFromEachOther = 0;
  for (int y = labelRows; y < kFrameHeight; ++y) {
    for (int x = 0; x < kFrameWidth; ++x) {
      if (x == divider) continue;
      const Image& expected = x < divider ? vsm : pcf;
      bool same = true, techniquesDiffer = false;
      for (int c = 0; c < 3; ++c) {
        same &= window.at(x, y, c) == expected.at(x, y, c);
        techniquesDiffer |= vsm.at(x, y, c) != pcf.at(x, y, c);
      }
      (x < divider ? leftMismatch : rightMismatch) += !same;
      differFromEachOther += techniquesDiffer;
    }
  }
  EXPECT_EQ(leftMismatch, 0);
  EXPECT_EQ(rightMismatch, 0);
  // Otherwise the test could not tell the sides apart.
  EXPECT_GT(differFromEachOther, 50);
}

// The error view's settings for the reference tests: three cascades with a blend band (the
// reference's blended path), a 15-tap Gaussian under 16x anisotropic filtering of a 1024² map (a
// wide kernel: at 480x270 a reference of about a second on llvmpipe's two cores), ESM so that
// the error is not zero.
fs::path writeReferenceSettings(const fs::path& folder, int width, int height) {
  const fs::path path = folder / "reference.json";
  writeFile(path,
            "{\"scene\": \"minification\", \"technique\": \"esm\", \"shadow-size\": 1024, "
            "\"blur\": 15, \"filter\": \"anisotropic\", \"aniso\": 16, \"cascades\": 3, "
            "\"cascade-blend\": 0.2, \"width\": " +
                std::to_string(width) + ", \"height\": " + std::to_string(height) + "}\n");
  return path;
}

// The viewer computes the error view's reference on a background thread: the window keeps
// drawing frames meanwhile. A reference computed in the frame (the window blocked) would draw
// none until it is done. The scripted run waits for it to complete and says how it went.
TEST(Viewer, KeepsDrawingFramesWhileTheReferenceComputes) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const fs::path settings = writeReferenceSettings(scratch.path(), 480, 270);
  const fs::path shot = scratch.path() / "error.png";
  const RunResult run = runViewer(settings, shot, scratch.path(), {"--show", "error"});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const BackgroundTiming reference = backgroundTiming(run.output, "filtered reference");
  // At 30 frames a second while it computes, a reference of a second or more leaves many frames;
  // the longest is a small part of the reference (a blocked window would spend all of it in one).
  EXPECT_GE(reference.frames, 5);
  EXPECT_LT(reference.longestMs, reference.jobMs / 4.0);
}

// Once complete, the error view equals the heat map of the renderer's own reference
// (Renderer::renderReference, the GPU path with its CPU completion) for the same settings,
// computed here headless.
TEST(Viewer, TheErrorViewOnceCompleteEqualsTheRenderersReference) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  constexpr int kWidth = 240, kHeight = 135;
  const fs::path settingsPath = writeReferenceSettings(scratch.path(), kWidth, kHeight);
  const fs::path shot = scratch.path() / "error.png";
  const RunResult run =
      runViewer(settingsPath, shot, scratch.path(), {"--show", "error", "--hide-panel"});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const Image window = readEncodedColorPng(shot);

  gl::Settings settings;
  gl::applySettingsFile(settingsPath, settings);
  gl::RenderSettings render = settings.render;
  render.technique = settings.techniques.front();
  render.lookupInputs = true;  // as the viewer renders: its views read the lit surfaces
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  const Scene scene = loadScene(settings.scene);
  renderer.setScene(scene);
  const gl::FrameView view{scene.camera, scene.light};
  const gl::RenderResult reference = renderer.renderReference(render, view, 1);
  const gl::RenderResult frame = renderer.render(render, view);
  const Image error =
      signedVisibilityError(frame.visibility, reference.visibility, litSurfaceMask(frame.lookup));
  Image expected(kWidth, kHeight, 3);
  int errorPixels = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 c = errorHeatColour(error.at(x, y), 0.5f);
      for (int i = 0; i < 3; ++i) expected.at(x, y, i) = std::round(c[i] * 255.0f) / 255.0f;
      errorPixels += std::abs(error.at(x, y)) > 0.01f;
    }
  }
  const Difference d = sceneAreaDifference(window, expected, kWidth, kHeight);
  std::cout << "error view against the renderer's reference: mean " << d.meanSteps
            << " steps, largest " << d.maxSteps << "; " << errorPixels
            << " pixels with an error over 0.01\n";
  // Otherwise the comparison would hold for any reference equal to the visibility.
  EXPECT_GT(errorPixels, kWidth * kHeight / 100);
  // The same shared code on the CPU and on llvmpipe: only float rounding may differ, which moves
  // a heat colour by a step where an error sits on a rounding boundary.
  EXPECT_LE(d.maxSteps, 2);
  EXPECT_LE(d.meanSteps, 0.01);
}

// The true shadow is traced on a background thread: with an area light (64 shadow rays a pixel,
// 0.25 to 2 s at 800x450 on two cores, with another test beside it under ctest -j2) the window
// keeps drawing meanwhile, none of its frames long. At least ten frames a second while it
// traces, so that the count scales with the trace: a window that waited for the trace would
// draw one frame at most (a CI run drew 4 in a 246 ms trace, under a fixed bound of 5).
TEST(Viewer, KeepsDrawingFramesWhileTheTrueShadowTraces) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const fs::path settings = scratch.path() / "soft.json";
  writeFile(settings,
            "{\"scene\": \"penumbrae\", \"technique\": \"pcf\", \"width\": 800, "
            "\"height\": 450, \"light\": {\"direction\": [0.3, -1, 0.2], \"size\": 0.05}}\n");
  const fs::path shot = scratch.path() / "truth.png";
  const RunResult run = runViewer(settings, shot, scratch.path(), {"--show", "truth-error"});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const BackgroundTiming trace = backgroundTiming(run.output, "true shadow");
  EXPECT_GE(trace.frames, std::max(2, int(trace.jobMs / 100.0)));
  EXPECT_LT(trace.longestMs, trace.jobMs / 4.0);
}

// The error against the ray-traced true shadow, once traced, is the render's visibility minus
// the truth in the report's heat map where both see the same surface, and marks the pixels where
// they do not: on `foliage` the alpha-tested leaves' edges, which the rasteriser's filtered alpha
// and the trace's cut differently. Computed here headless with the library (render, its camera
// depth, the trace and the surface match) for the same settings.
TEST(Viewer, TheTrueShadowErrorViewMarksSilhouettesAndIsZeroOnLitGround) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  constexpr int kWidth = 320, kHeight = 180;
  const fs::path settingsPath = scratch.path() / "truth.json";
  writeFile(settingsPath,
            "{\"scene\": \"foliage\", \"technique\": \"pcf\", \"shadow-size\": 1024, "
            "\"blur\": 3, \"filter\": \"bilinear\", \"width\": 320, \"height\": 180}\n");
  const fs::path shot = scratch.path() / "truth.png";
  const RunResult run =
      runViewer(settingsPath, shot, scratch.path(), {"--show", "truth-error", "--hide-panel"});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  const Image window = readEncodedColorPng(shot);

  gl::Settings settings;
  gl::applySettingsFile(settingsPath, settings);
  gl::RenderSettings render = settings.render;
  render.technique = settings.techniques.front();
  render.lookupInputs = true;  // as the viewer renders: its views read the lit surfaces
  gl::HeadlessContext context;
  gl::Renderer renderer(context);
  const Scene scene = loadScene(settings.scene);
  renderer.setScene(scene);
  const gl::FrameView view{scene.camera, scene.light};
  const gl::RenderResult frame = renderer.render(render, view);
  truth::TrueShadowRequest request;
  request.camera = scene.camera;
  request.light = scene.light;
  request.viewBounds = scene.viewBounds();
  request.width = kWidth;
  request.height = kHeight;
  request.supersample = 1;
  const truth::RayScene rayScene(scene);
  const truth::TrueShadow trace = truth::traceTrueShadow(rayScene, request);
  const truth::SurfaceMatch match =
      truth::matchRasterisedSurfaces(trace, renderer.readCameraDepth(), request);

  Image coverage = litSurfaceMask(frame.lookup);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (match.matched.at(x, y) == 0.0f || trace.visibility.at(x, y) < 0.0f ||
          trace.reachedByLight.at(x, y) == 0.0f) {
        coverage.at(x, y) = 0;
      }
    }
  }
  const Image error = signedVisibilityError(frame.visibility, trace.visibility, coverage);
  Image expected(kWidth, kHeight, 3);
  int errorPixels = 0, litGround = 0, litGroundZero = 0, marked = 0;
  const glm::vec3 zero = errorHeatColour(0.0f, viewer::kErrorRange);
  const auto shows = [&](int x, int y, glm::vec3 bytes) {
    for (int i = 0; i < 3; ++i) {
      if (std::lround(window.at(x, y, i) * 255.0f) != std::lround(bytes[i])) return false;
    }
    return true;
  };
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      glm::vec3 bytes;
      if (match.matched.at(x, y) == 0.0f) {
        bytes = glm::vec3(viewer::kSilhouetteColour[0], viewer::kSilhouetteColour[1],
                          viewer::kSilhouetteColour[2]);
        marked += shows(x, y, bytes);
      } else if (trace.visibility.at(x, y) < 0.0f) {
        bytes = glm::vec3(viewer::kNoSurfaceColour[0], viewer::kNoSurfaceColour[1],
                          viewer::kNoSurfaceColour[2]);
      } else if (litSurfaceMask(frame.lookup).at(x, y) > 0.0f &&
                 trace.reachedByLight.at(x, y) == 0.0f) {
        bytes = glm::vec3(viewer::kTerminatorColour[0], viewer::kTerminatorColour[1],
                          viewer::kTerminatorColour[2]);
      } else {
        bytes = glm::round(errorHeatColour(error.at(x, y), viewer::kErrorRange) * 255.0f);
        errorPixels += std::abs(error.at(x, y)) > 0.05f;
        // Open ground in the light: lit in the render and in the truth.
        if (coverage.at(x, y) > 0.0f && frame.visibility.at(x, y) == 1.0f &&
            trace.visibility.at(x, y) == 1.0f) {
          ++litGround;
          litGroundZero += shows(x, y, glm::round(zero * 255.0f));
        }
      }
      for (int i = 0; i < 3; ++i) expected.at(x, y, i) = bytes[i] / 255.0f;
    }
  }
  const Difference d = sceneAreaDifference(window, expected, kWidth, kHeight);
  std::cout << "true-shadow error view against the library's: mean " << d.meanSteps
            << " steps, largest " << d.maxSteps << "; " << match.excludedPixels
            << " silhouette pixels (" << marked << " marked), " << errorPixels
            << " pixels with an error over 0.05, " << litGround << " lit ground pixels\n";
  // A picture worth comparing: silhouettes to mark, errors to show, open ground lit.
  EXPECT_GT(match.excludedPixels, 50);
  EXPECT_GT(errorPixels, kWidth * kHeight / 100);
  EXPECT_GT(litGround, kWidth * kHeight / 5);
  // Every silhouette pixel marked, zero error on the lit ground, the rest the heat map.
  EXPECT_EQ(marked, match.excludedPixels);
  EXPECT_EQ(litGroundZero, litGround);
  EXPECT_LE(d.maxSteps, 2);
  EXPECT_LE(d.meanSteps, 0.01);
  EXPECT_NE(run.output.find("silhouettes: " + std::to_string(match.excludedPixels) + " pixels"),
            std::string::npos)
      << run.output;
}

// A split view saved by the viewer loads back with both sides: the file holds the right side
// under "split", and `penumbra render --settings` of it renders the left side.
TEST(Viewer, SavesAndLoadsBothSidesOfTheSplitView) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const fs::path settings = writeSettings(scratch.path(), "backyard", Technique::Vsm);
  const fs::path shot = scratch.path() / "split.png";
  const fs::path saved = scratch.path() / "saved.json";
  const RunResult run = runViewer(settings, shot, scratch.path(),
                                  {"--split", "pcf", "--save-settings", saved.string()});
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  gl::Settings read;
  gl::applySettingsFile(saved, read);
  ASSERT_TRUE(read.split.has_value()) << readFile(saved);
  EXPECT_EQ(read.split->technique, Technique::Pcf);
  EXPECT_EQ(read.techniques, std::vector<Technique>{Technique::Vsm});
  // Loaded without --split, the saved file opens the same split view.
  const fs::path again = scratch.path() / "again.png";
  const RunResult reload = runViewer(saved, again, scratch.path());
  ASSERT_EQ(reload.exitCode(), 0) << reload.output;
  EXPECT_EQ(sceneAreaDifference(readEncodedColorPng(shot), readEncodedColorPng(again), kFrameWidth,
                                kFrameHeight)
                .maxSteps,
            0);
  // The command line takes the file and renders the left side.
  const fs::path out = scratch.path() / "render";
  const RunResult render =
      runPenumbra({"render", "--settings", saved.string(), "--out", out.string()}, scratch.path());
  ASSERT_EQ(render.exitCode(), 0) << render.output;
  EXPECT_TRUE(fs::exists(out / "backyard_vsm.png"));
  EXPECT_FALSE(fs::exists(out / "backyard_pcf.png"));
}

// A hostile scene file (docs/untrusted-input.md) ends the viewer with one line naming it, as it
// ends render and compare: the issue's 20,000-level node chain crashed it (SIGSEGV), and
// --max-memory bounds what a file may expand to.
TEST(Viewer, RefusesAHostileSceneFileInOneLine) {
  REQUIRE_XVFB();
  ScratchFolder scratch;
  const std::vector<glm::vec3> quad{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}};
  std::string chain = "[";
  for (int i = 0; i + 1 < 20000; ++i) chain += R"({"children":[)" + std::to_string(i + 1) + "]},";
  const fs::path deep = penumbra::testing::writeFile(
      scratch.path() / "deep.gltf",
      penumbra::testing::gltfWithMesh(quad, {0, 1, 2}, chain + R"({"mesh":0}])", "[0]"));
  const fs::path settings = scratch.path() / "deep.json";
  writeFile(settings, "{\"scene\": \"" + deep.string() + "\", \"width\": 160, \"height\": 90}\n");
  const RunResult run = runViewer(settings, scratch.path() / "deep.png", scratch.path());
  EXPECT_EQ(run.exitCode(), 1) << run.output;
  EXPECT_EQ(run.output, "penumbra-viewer: " + deep.string() +
                            ": the node hierarchy is deeper than 1024 levels (node 1024 is at "
                            "level 1025 below root 0); penumbra loads at most 1024 levels\n");

  const penumbra::testing::Grid g = penumbra::testing::grid(64);
  const fs::path instances = penumbra::testing::writeFile(
      scratch.path() / "instances.gltf",
      penumbra::testing::gltfWithMesh(g.positions, g.indices, R"([{"mesh":0},{"mesh":0}])",
                                      "[0,1]"));
  writeFile(settings,
            "{\"scene\": \"" + instances.string() + "\", \"width\": 160, \"height\": 90}\n");
  const RunResult budget =
      runViewer(settings, scratch.path() / "instances.png", scratch.path(), {"--max-memory", "1M"});
  EXPECT_EQ(budget.exitCode(), 1) << budget.output;
  EXPECT_TRUE(budget.output.starts_with("penumbra-viewer: " + instances.string() + ": needs 1.") &&
              budget.output.ends_with(" above the 1.00 MiB limit (--max-memory)\n"))
      << budget.output;
}

}  // namespace
}  // namespace penumbra::test
