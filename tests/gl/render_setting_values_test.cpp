// The render settings' names and device-independent ranges (penumbra/gl/render_setting_values.h):
// what the command line, settings files and the viewer share, checked before any GL work.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "penumbra/error.h"
#include "penumbra/gl/render_setting_values.h"

namespace penumbra::gl {
namespace {

std::string messageOf(const auto& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

TEST(RenderSettingValues, UnknownNamesListTheValidOnes) {
  EXPECT_EQ(parseBlurKernel("box"), BlurKernel::Box);
  EXPECT_EQ(parseOverlay("cascades"), Overlay::Cascades);
  EXPECT_TRUE(parseCascadeDepth("fitted"));
  EXPECT_FALSE(parseCascadeDepth("fixed"));
  EXPECT_EQ(messageOf([] { parseBlurKernel("gauss"); }),
            "unknown blur kernel 'gauss'; valid kernels: gaussian, box");
  EXPECT_EQ(messageOf([] { parseOverlay("tint"); }),
            "unknown overlay 'tint'; valid overlays: none, cascades");
  EXPECT_EQ(messageOf([] { parseCascadeDepth("fit"); }),
            "unknown cascade depth 'fit'; valid depths: fixed, fitted");
}

TEST(RenderSettingValues, BlurTapsAreOddWidthsUpToTheLargestKernel) {
  EXPECT_EQ(blurRadiusOfTaps(1), 0);
  EXPECT_EQ(blurRadiusOfTaps(9), 4);
  EXPECT_EQ(blurRadiusOfTaps(kMaxBlurTaps), shaders::kMaxBlurRadius);
  for (int taps : {-1, 0, 2, 8, kMaxBlurTaps + 2}) {
    EXPECT_THROW(blurRadiusOfTaps(taps), Error) << taps;
  }
}

TEST(RenderSettingValues, DefaultSigmaIsHalfTheRadiusAndAtLeastHalfATexel) {
  EXPECT_EQ(defaultBlurSigma(0), 0.5f);
  EXPECT_EQ(defaultBlurSigma(1), 0.5f);
  EXPECT_EQ(defaultBlurSigma(4), 2.0f);
  EXPECT_EQ(defaultBlurSigma(shaders::kMaxBlurRadius), 32.0f);
}

TEST(RenderSettingValues, RefusesWhatNoGlCouldRenderWithTheRange) {
  EXPECT_NO_THROW(validateRenderSettings(RenderSettings{}));
  const auto refused = [](auto set) {
    RenderSettings s;
    set(s);
    return messageOf([&] { validateRenderSettings(s); });
  };
  EXPECT_EQ(refused([](RenderSettings& s) { s.blur.sigma = NAN; }),
            "blur sigma nan is out of range [0.01, 64]");
  EXPECT_EQ(refused([](RenderSettings& s) { s.blur.sigma = 0.0f; }),
            "blur sigma 0 is out of range [0.01, 64]");
  EXPECT_EQ(refused([](RenderSettings& s) { s.shadowMapSize = 8; }),
            "shadow-map size 8 is out of range [16, 16384]");
  EXPECT_EQ(refused([](RenderSettings& s) { s.width = 0; }),
            "frame width 0 is out of range [1, 16384]");
  EXPECT_EQ(refused([](RenderSettings& s) { s.msaaSamples = 3; }),
            "MSAA samples 3: valid values are 1 (off), 2, 4, 8");
  EXPECT_NE(refused([](RenderSettings& s) {
              s.cascades.maxDistance = 1e30f;
            }).find("shadow distance (--shadow-distance) 1e+30 is out of range [0, 1e6]"),
            std::string::npos);
  EXPECT_NE(refused([](RenderSettings& s) { s.cascades.lambda = NAN; }), "accepted");
}

}  // namespace
}  // namespace penumbra::gl
