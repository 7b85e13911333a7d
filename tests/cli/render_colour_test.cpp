// The colour pictures `render` writes are sRGB: the linear light the camera pass shades is
// encoded once on the way to the PNG (penumbra/srgb.h), for a single render and for every frame
// of a --frames sequence. Planar scene: the light falls straight down, so the lit ground reads
// its albedo and the shadowed ground albedo x ambient, both in linear light.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <tuple>

#include "penumbra/gl/renderer.h"
#include "penumbra/image_io.h"
#include "penumbra/scene.h"
#include "penumbra/srgb.h"
#include "run_penumbra.h"

namespace penumbra::test {
namespace {

using Rgb = std::tuple<int, int, int>;

Rgb encoded(glm::vec3 linear) {
  auto byte = [](float v) { return int(std::lround(255.0f * srgbFromLinear(v))); };
  return {byte(linear.r), byte(linear.g), byte(linear.b)};
}

// Pixels within one 8-bit step of `colour` in every channel.
int pixelsNear(const Image& png, Rgb colour) {
  int count = 0;
  for (int y = 0; y < png.height(); ++y) {
    for (int x = 0; x < png.width(); ++x) {
      const int r = int(std::lround(png.at(x, y, 0) * 255.0f));
      const int g = int(std::lround(png.at(x, y, 1) * 255.0f));
      const int b = int(std::lround(png.at(x, y, 2) * 255.0f));
      count += std::abs(r - std::get<0>(colour)) <= 1 && std::abs(g - std::get<1>(colour)) <= 1 &&
               std::abs(b - std::get<2>(colour)) <= 1;
    }
  }
  return count;
}

void expectGroundEncodedOnce(const Image& png, const std::string& what) {
  const glm::vec3 ground = makeBuiltinScene("planar").meshes.front().albedo;
  const float ambient = gl::RenderSettings{}.ambient;
  const int pixels = png.width() * png.height();
  // The lit ground is most of the picture, the shadow a good part of the rest.
  EXPECT_GT(pixelsNear(png, encoded(ground)), pixels / 3) << what;
  EXPECT_GT(pixelsNear(png, encoded(ground * ambient)), pixels / 50) << what;
  // Written as it is (0.75 -> 191) or encoded twice (0.75 -> 242), the ground is absent.
  const auto byte = [](float v) { return int(std::lround(255.0f * v)); };
  EXPECT_EQ(pixelsNear(png, {byte(ground.r), byte(ground.g), byte(ground.b)}), 0) << what;
  const glm::vec3 twice(srgbFromLinear(ground.r), srgbFromLinear(ground.g),
                        srgbFromLinear(ground.b));
  EXPECT_EQ(pixelsNear(png, encoded(twice)), 0) << what;
}

TEST(RenderColour, TheColourPngHoldsTheSrgbEncodingOfTheShadedLinearLight) {
  ScratchFolder scratch;
  const RunResult run =
      runPenumbra({"render", "--scene", "planar", "--technique", "pcf", "--shadow-size", "256",
                   "--width", "96", "--height", "54", "--out", "out"},
                  scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  expectGroundEncodedOnce(readEncodedColorPng(scratch.path() / "out" / "planar_pcf.png"),
                          "planar_pcf.png");
}

TEST(RenderColour, EveryFrameOfASequenceIsEncodedOnce) {
  ScratchFolder scratch;
  const RunResult run = runPenumbra(
      {"render", "--scene", "planar", "--technique", "pcf", "--shadow-size", "256", "--width", "96",
       "--height", "54", "--frames", "2", "--animate", "dolly", "--out", "out"},
      scratch.path());
  ASSERT_EQ(run.exitCode(), 0) << run.output;
  for (const char* frame : {"planar_pcf_0000.png", "planar_pcf_0001.png"}) {
    expectGroundEncodedOnce(readEncodedColorPng(scratch.path() / "out" / "frames" / frame), frame);
  }
}

}  // namespace
}  // namespace penumbra::test
