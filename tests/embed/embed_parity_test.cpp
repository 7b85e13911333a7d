// examples/embed, a host that is not penumbra (its own window, scene, light pass and shader),
// against `penumbra render` of the OBJ it writes with the same settings: for each technique its
// visibility equals render's, from a window-depth map and from a linear-depth map, and
// filter() leaves the host's GL state, error queue and debug callback as it found them.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/image_io.h"
#include "penumbra/run_program.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// What the example and render are both given: the same view, frame, map and prefilter.
// clang-format off
const std::vector<std::string> kSharedOptions{
    "--light-dir", "0.75,-1,-0.5", "--camera-pos", "0,3.5,6", "--camera-target", "0,0.5,0",
    "--camera-fov", "45", "--width", "320", "--height", "180", "--blur", "3",
    "--filter", "bilinear"};
// clang-format on
constexpr const char* kShadowSize = "512";

// The host's light pass writes penumbra's linear metric into R32F with the arithmetic of
// render's light pass, and its shader computes the receiver's the same way: the same bits
// reach the same lookup. kArithmetic, lookup parity's fp32 allowance, leaves room for a driver
// that contracts the two sides' expressions differently (measured: 0 on every pixel).
constexpr float kArithmetic = 1e-5f;

// The host's D32F window depth is the same metric (an orthographic light's window depth is
// (distance - near) / (far - near) with fitLightView's near and far), but the rasteriser
// interpolates it from the vertices where render's light pass evaluates it per fragment: the
// maps differ by up to 9 ulps (3e-7 at 512^2, in 60 % of the covered texels). Reconstruction
// amplifies that where it cancels: VSM's variance m2 - m1^2 falls to its floor (1e-5) on lit
// receivers, and MSM solves its Hamburger system on unorm16 moments, so on shadow edges a few
// pixels move by up to 1e-3 (VSM) and 1e-2 (MSM, measured 0.0115); elsewhere the difference is
// the receiver's fp32 rounding (1e-5). So all but lookup parity's share of pixels (0.1 %) lie
// within kWindowBulk, and every pixel within kWindowMax, but where a depth test or ESM's
// classification decides: a tie there may flip a pixel whole (none did here).
constexpr double kPixelShare = 0.001;
constexpr float kWindowBulk = 1e-3f;
constexpr float kWindowMax = 0.02f;
// Where ties decide, pixels flipped whole: none measured; a tie needs the map and the receiver
// within the 9-ulp map rounding, so a handful at most (0.01% of the 320x180 frame).
constexpr size_t kTiePixels = 6;

struct EmbedCase {
  std::string name;       // the test's name
  std::string technique;  // its id
  std::vector<std::string> params;
  bool decidesAtTies;  // a depth test or a classification: kWindowMax does not hold
};

std::string readLog(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `args` with its output in `log`; the log's text when it fails.
::testing::AssertionResult runLogged(const std::vector<std::string>& args, const fs::path& log) {
  fs::remove(log);
  const ProgramResult result = runProgram(args, log);
  if (result.succeeded()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << args[0] << " ... exited " << result.exitCode
                                       << " (started: " << result.started << "):\n"
                                       << readLog(log);
}

// A little-endian float PFM (scale < 0) of one channel, rows bottom to top, as row 0 at the top.
Image readPfm(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int width = 0, height = 0;
  float scale = 0.0f;
  in >> magic >> width >> height >> scale;
  in.get();  // the one whitespace byte before the data
  if (magic != "Pf" || width <= 0 || height <= 0 || scale >= 0.0f) {
    throw std::runtime_error(path.string() + " is no little-endian grey PFM");
  }
  Image image(width, height, 1);
  for (int y = height - 1; y >= 0; --y) {
    for (int x = 0; x < width; ++x) {
      unsigned char b[4] = {};
      in.read(reinterpret_cast<char*>(b), 4);
      image.at(x, y, 0) = std::bit_cast<float>(uint32_t(b[0]) | uint32_t(b[1]) << 8 |
                                               uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
    }
  }
  if (!in) throw std::runtime_error(path.string() + " is shorter than its header says");
  return image;
}

// |host - render| per pixel, sorted.
struct Differences {
  std::vector<float> values;
  float quantile(double q) const {
    return values[std::min(values.size() - 1, size_t(q * double(values.size())))];
  }
  float max() const { return values.back(); }
  size_t countAbove(float limit) const {
    return size_t(values.end() - std::upper_bound(values.begin(), values.end(), limit));
  }
  std::string describe() const {
    std::ostringstream text;
    text << values.size() << " pixels, p99 " << quantile(0.99) << ", p99.9 " << quantile(0.999)
         << ", max " << max();
    return text.str();
  }
};

Differences differencesOf(const Image& host, const Image& render) {
  Differences d;
  for (int y = 0; y < host.height(); ++y) {
    for (int x = 0; x < host.width(); ++x) {
      d.values.push_back(std::abs(host.at(x, y, 0) - render.at(x, y, 0)));
    }
  }
  std::sort(d.values.begin(), d.values.end());
  return d;
}

void PrintTo(const EmbedCase& c, std::ostream* out) {
  *out << c.name;
}

bool haveXvfbRun() {
  return runProgram({"xvfb-run", "--help"}).started;
}

class EmbedParity : public ::testing::TestWithParam<EmbedCase> {};

TEST_P(EmbedParity, VisibilityEqualsRenderOfTheSameSceneAndHostStateIsKept) {
  if (!haveXvfbRun()) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true") FAIL() << "xvfb-run is not installed";
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs xvfb)";
  }
  const EmbedCase& c = GetParam();
  const fs::path dir = fs::path(EMBED_RUNS_DIR) / c.name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path obj = dir / "embed_scene.obj";
  std::vector<std::string> params;
  for (const std::string& p : c.params) params.insert(params.end(), {"--param", p});

  // The example writes its scene, then render draws it.
  std::map<std::string, Image> host;
  for (const std::string depth : {"window", "linear"}) {
    const fs::path pfm = dir / (depth + ".pfm");
    // --check-state: the example exits 1 naming every state filter() changed.
    std::vector<std::string> args{"xvfb-run", "-a", "-s", "-screen 0 640x480x24", EMBED_EXECUTABLE};
    args.insert(args.end(), {"--technique", c.technique, "--depth", depth, "--size", kShadowSize,
                             "--write-obj", obj.string(), "--out", pfm.string(), "--check-state"});
    args.insert(args.end(), params.begin(), params.end());
    args.insert(args.end(), kSharedOptions.begin(), kSharedOptions.end());
    ASSERT_TRUE(runLogged(args, dir / (depth + ".log")));
    host[depth] = readPfm(pfm);
  }
  std::vector<std::string> args{PENUMBRA_EXECUTABLE, "render", "--scene", obj.string()};
  args.insert(args.end(), {"--technique", c.technique, "--shadow-size", kShadowSize,
                           "--blur-kernel", "box", "--out", (dir / "render").string()});
  args.insert(args.end(), params.begin(), params.end());
  args.insert(args.end(), kSharedOptions.begin(), kSharedOptions.end());
  ASSERT_TRUE(runLogged(args, dir / "render.log"));
  const Image render =
      readFloatExr(dir / "render" / ("embed_scene_" + c.technique + "_visibility.exr"));

  for (const auto& [depth, image] : host) {
    ASSERT_EQ(image.width(), render.width());
    ASSERT_EQ(image.height(), render.height());
  }
  const Differences linear = differencesOf(host["linear"], render);
  const Differences window = differencesOf(host["window"], render);
  std::cout << c.name << " linear depth: " << linear.describe() << "\n"
            << c.name << " window depth: " << window.describe() << "\n";
  EXPECT_LE(linear.max(), kArithmetic) << "linear depth: " << linear.describe();
  EXPECT_LE(window.quantile(1.0 - kPixelShare), kWindowBulk)
      << "window depth: " << window.describe();
  if (!c.decidesAtTies) {
    EXPECT_LE(window.max(), kWindowMax) << "window depth: " << window.describe();
  } else {
    EXPECT_LE(window.countAbove(kWindowMax), kTiePixels) << "window depth: " << window.describe();
  }
}

// Hard and ESM's fallback test raw depth; the rest reconstruct filtered channels (moments,
// exponentials, the power CDF's min/max/mean). ESM twice: the threshold classifier, and the
// Z-max pyramid's (a third texture the host's shader samples).
INSTANTIATE_TEST_SUITE_P(
    Techniques, EmbedParity,
    ::testing::Values(EmbedCase{"hard", "hard", {}, true}, EmbedCase{"vsm", "vsm", {}, false},
                      EmbedCase{"evsm4", "evsm4", {}, false}, EmbedCase{"esm", "esm", {}, true},
                      EmbedCase{"esm_zmax", "esm", {"esm.classifier=zmax"}, true},
                      EmbedCase{"msm", "msm", {}, false},
                      EmbedCase{"powercdf", "powercdf", {}, false}),
    [](const ::testing::TestParamInfo<EmbedCase>& param) { return param.param.name; });

}  // namespace
}  // namespace penumbra
