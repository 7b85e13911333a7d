// bench --passes: every prefilter pass of a filtered technique is measured beside its minimal
// kernel; techniques without a prefilter are refused.
#include "penumbra/gl/pass_bench.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "gl_test_context.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

class PassBench : public testing::GlTest {};

gl::RenderSettings small(Technique technique) {
  gl::RenderSettings s;
  s.technique = technique;
  s.shadowMapSize = 128;
  s.width = 32;
  s.height = 18;
  return s;
}

void expectTimed(const gl::PassBenchResult& r, const std::vector<std::string>& passes) {
  ASSERT_EQ(r.passes.size(), passes.size());
  for (size_t i = 0; i < passes.size(); ++i) {
    EXPECT_EQ(r.passes[i].pass, passes[i]);
    EXPECT_TRUE(r.passes[i].passMs() > 0.0 && std::isfinite(r.passes[i].passMs())) << passes[i];
    EXPECT_TRUE(r.passes[i].baselineMs() > 0.0 && std::isfinite(r.passes[i].baselineMs()))
        << passes[i];
  }
}

// The ratios use each side's fastest frame (llvmpipe's slow mode, both rasteriser threads on one
// core, doubles a pass on some frames and not others); the median is reported beside it.
TEST(PassBenchTimes, RatiosUseTheFastestFrameWithTheMedianBeside) {
  const gl::FrameTimes t = gl::frameTimes({8.4, 4.2, 8.1, 4.3, 8.6});
  EXPECT_EQ(t.fastestMs, 4.2);
  EXPECT_EQ(t.medianMs, 8.1);
  gl::PassTiming row;
  row.passTimes = t;
  row.baselineTimes = gl::frameTimes({3.5, 7.0, 7.2});
  EXPECT_DOUBLE_EQ(row.ratio(), 4.2 / 3.5);
  EXPECT_EQ(gl::frameTimes({}).fastestMs, 0.0);  // no frames: no time, and ratio() 0
}

TEST_F(PassBench, MeasuresEveryPrefilterPassBesideItsMinimalKernel) {
  gl::Renderer renderer(*context);
  // RGBA32F: the separate passes, and the fused one beside the plain fused kernel of its traffic.
  const gl::PassBenchResult evsm =
      gl::benchPasses(renderer, makeBuiltinScene("planar"), small(Technique::Evsm4), 2);
  EXPECT_EQ(evsm.format, "rgba32f x 1 layer");
  EXPECT_EQ(evsm.timing, gl::passTimingDescription(renderer));
  expectTimed(evsm, {"encode", "prefilter", "mips", "camera", "encode + prefilter, fused"});
  EXPECT_EQ(evsm.passes[4].baseline, "plain fused tile blur of depth, 5 taps");
  // Each row's sides timed alike: the separate encode and its copy, the camera pass and its
  // lookup several times a frame, the others once (2 frames).
  const int perFrame[] = {gl::kEncodeDispatchesPerFrame, 1, 1, gl::kCameraDrawsPerFrame, 1};
  for (size_t i = 0; i < evsm.passes.size(); ++i) {
    EXPECT_EQ(evsm.passes[i].passTimes.samples, 2 * perFrame[i]) << evsm.passes[i].pass;
    EXPECT_EQ(evsm.passes[i].baselineTimes.samples, 2 * perFrame[i]) << evsm.passes[i].pass;
  }
  // R32F: the fused pass's and its minimal kernel's one-component tiles compile and run.
  const gl::PassBenchResult esm =
      gl::benchPasses(renderer, makeBuiltinScene("planar"), small(Technique::Esm), 1);
  EXPECT_EQ(esm.format, "r32f x 1 layer");
  // ESM's camera pass beside a lookup that falls back as it does, and with the classification off
  // beside the least lookup.
  expectTimed(esm, {"encode", "prefilter", "mips", "camera", "camera, classification off",
                    "encode + prefilter, fused"});
  EXPECT_EQ(esm.passes[3].baseline,
            "minimal lookup: each layer filtered once, reconstruct with the threshold test, and "
            "where it fails the pass's own PCF fallback (the light's depth, a receiver plane from "
            "screen derivatives), Lambert, RGBA8");
  const std::string leastLookup =
      "minimal lookup: each layer filtered once, reconstruct, Lambert, RGBA8";
  EXPECT_EQ(esm.passes[4].baseline, leastLookup);
  gl::RenderSettings paperFallback = small(Technique::Esm);
  paperFallback.params.esm.fallback = shaders::kEsmFallbackPaper;
  EXPECT_EQ(
      gl::benchPasses(renderer, makeBuiltinScene("planar"), paperFallback, 1).passes[3].baseline,
      "minimal lookup: each layer filtered once, reconstruct with the threshold test, and where "
      "it fails the paper's 2x2 fallback, Lambert, RGBA8");
  gl::RenderSettings unclassified = small(Technique::Esm);
  unclassified.params.esm.classifier = shaders::kEsmClassifyNone;  // nothing falls back
  const gl::PassBenchResult plain =
      gl::benchPasses(renderer, makeBuiltinScene("planar"), unclassified, 1);
  expectTimed(plain, {"encode", "prefilter", "mips", "camera", "encode + prefilter, fused"});
  EXPECT_EQ(plain.passes[3].baseline, leastLookup);
  // The Z-max classifier: no yardstick classifies as it does, so its pass stands beside the least
  // lookup, which says what it leaves out, and with the classification off beside it too.
  gl::RenderSettings zmax = small(Technique::Esm);
  zmax.params.esm.classifier = shaders::kEsmClassifyZmax;
  const gl::PassBenchResult pyramid =
      gl::benchPasses(renderer, makeBuiltinScene("planar"), zmax, 1);
  expectTimed(pyramid, {"encode", "prefilter", "mips", "camera", "camera, classification off",
                        "encode + prefilter, fused"});
  EXPECT_EQ(pyramid.passes[3].baseline,
            "minimal lookup: each layer filtered once, reconstruct (no classification or "
            "fallback, which the pass has), Lambert, RGBA8");
  EXPECT_EQ(pyramid.passes[4].baseline, leastLookup);
  // The yardstick (rawblur's kernels on a 2D texture of the same components) beside the encode,
  // the blur and the fused pass; the mips and the camera pass have none.
  const std::vector<std::string> yardsticks{"rawblur copy, rgba32f",
                                            "rawblur blur, 5 taps, rgba32f", "", "",
                                            "rawblur copy + blur, 5 taps, rgba32f"};
  for (size_t i = 0; i < yardsticks.size(); ++i) {
    EXPECT_EQ(evsm.passes[i].yardstick, yardsticks[i]);
    EXPECT_EQ(evsm.passes[i].yardstickMs() > 0.0, !yardsticks[i].empty()) << evsm.passes[i].pass;
    EXPECT_TRUE(std::isfinite(evsm.passes[i].yardstickMs())) << evsm.passes[i].pass;
  }
  // 16-bit storage rounds the blur's intermediate: no fused pass.
  expectTimed(gl::benchPasses(renderer, makeBuiltinScene("planar"), small(Technique::Msm), 1),
              {"encode", "prefilter", "mips", "camera"});
  // The summed-area filter: encode and the table, no blur.
  gl::RenderSettings sat = small(Technique::Vsm);
  sat.filter = gl::FilterMode::SummedArea;
  const gl::PassBenchResult summed = gl::benchPasses(renderer, makeBuiltinScene("planar"), sat, 1);
  ASSERT_NO_FATAL_FAILURE(expectTimed(summed, {"encode", "summed-area table", "camera"}));
  // Its camera pass stands beside a yardstick that reads the table, not the channel texture.
  EXPECT_EQ(summed.passes[2].baseline,
            "minimal lookup: each channel's mean over the blur's box from the table, reconstruct, "
            "Lambert, RGBA8");
}

// The camera pass's yardstick draws the same picture, less what it leaves out: no normal offset,
// no receiver plane but under ESM's fallback, the channels through the pass's filter mode
// (trilinear: at the level of the footprint from screen derivatives) or the summed-area table's
// box of the blur's width. On a flat-lit scene that changes the shadows' edges only. The power
// CDF's min and max channels and ESM's log-space one are reduced by hand as the pass's are:
// averaged by the hardware they shade other pixels.
TEST_F(PassBench, TheMinimalLookupDrawsTheCameraPassPicture) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("backyard");
  for (const char* id : {"vsm", "csm", "powercdf", "esm", "esm-paper", "esm-log", "vsm-sat",
                         "lvsm-sat", "vsm-trilinear", "powercdf-trilinear"}) {
    SCOPED_TRACE(id);
    const std::string_view name(id);
    const std::string_view variant =
        name.find('-') == std::string_view::npos ? "" : name.substr(name.find('-') + 1);
    const Technique t = parseTechnique(std::string(name.substr(0, name.find('-'))));
    const bool summedArea = variant == "sat";
    gl::RenderSettings s = small(t);
    if (variant == "log") s.params.esm.filterSpace = shaders::kEsmFilterLog;
    if (variant == "paper") s.params.esm.fallback = shaders::kEsmFallbackPaper;
    s.shadowMapSize = 512;
    s.width = 160;
    s.height = 90;
    s.filter = summedArea               ? gl::FilterMode::SummedArea
               : variant == "trilinear" ? gl::FilterMode::Trilinear
                                        : gl::FilterMode::Bilinear;
    const gl::RenderResult frame = renderer.render(scene, s);
    // ESM's yardstick with and without its classification and fallback.
    for (const bool esmFallback :
         t == Technique::Esm ? std::vector{false, true} : std::vector{false}) {
      SCOPED_TRACE(esmFallback ? "with ESM's fallback" : "");
      EXPECT_GT(renderer.timeMinimalLookup(esmFallback), 0.0);
      const Image minimal = renderer.readMinimalLookupColor();
      ASSERT_EQ(minimal.width(), s.width);
      ASSERT_EQ(minimal.height(), s.height);
      int near = 0, nearUnclassified = 0, shadowed = 0, fellBack = 0;
      for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
          float difference = 0.0f;
          for (int c = 0; c < 3; ++c) {
            difference =
                std::max(difference, std::abs(minimal.at(x, y, c) - frame.color.at(x, y, c)));
          }
          // 8 bits of the yardstick's target (1/255) and a shadow edge's shift of a texel.
          const bool agrees = difference < 0.02f;
          const bool failed = t == Technique::Esm && frame.diagnostic.at(x, y) == 1.0f;
          near += agrees ? 1 : 0;
          nearUnclassified += agrees && !failed ? 1 : 0;
          fellBack += failed ? 1 : 0;
          if (frame.visibility.at(x, y) < 0.5f) ++shadowed;
        }
      }
      const int pixels = s.width * s.height;
      EXPECT_GT(shadowed, pixels / 50) << "the view must show shadows for this to test them";
      // Every pixel: the same filter mode on both sides (trilinear: the yardstick at level 0
      // moved 531 pixels of VSM, 610 of the power CDF), no normal offset asked for, and
      // none of these techniques' lookups reads the receiver plane but ESM's fallback, whose
      // plane the yardstick solves from screen derivatives (measured: all agree). Averaged
      // by the hardware, the power CDF's min and max channels moved 149 pixels, ESM's log-space
      // channel 24.
      // The summed-area lookup widens its box to the pixel's footprint where that is wider than
      // the blur, the yardstick keeps the blur's box: at grazing angles on the far ground only
      // (measured: 1 pixel of 14400 for VSM and LVSM). 0.1% leaves room for other drivers'
      // derivatives at those pixels; the yardstick reading a wrong channel moved 650-950.
      if (summedArea) {
        EXPECT_GE(near, pixels - pixels / 1000);
      } else if (t == Technique::Esm && !esmFallback) {
        // Where the pass fell back, the yardstick without a fallback shades otherwise: every
        // other pixel agrees.
        EXPECT_EQ(nearUnclassified, pixels - fellBack);
        EXPECT_LT(near, pixels);
      } else if (t == Technique::Esm) {
        // With the fallback, whose receiver plane the yardstick solves from screen derivatives:
        // all agree here; without that plane it moved 240 pixels, without the fallback 49
        // (measured). 0.1% leaves room for other drivers' derivatives, as for the table.
        EXPECT_GE(near, pixels - pixels / 1000);
      } else {
        EXPECT_EQ(near, pixels);
      }
      if (t == Technique::Esm) {
        EXPECT_GT(fellBack, pixels / 50) << "the view must show ESM's fallback to test it";
      }
      std::printf("%s%s: %d of %d pixels agree, %d shadowed, %d fell back\n", id,
                  esmFallback ? " with its fallback" : "", near, pixels, shadowed, fellBack);
    }
  }
}

// ESM's two camera rows time what they name. The first row's yardstick is the lookup with the
// fallback and the second's the least lookup, each drawn after a warm-up frame and then once
// after each of the camera pass's draws. The second row is timed last: the pass's and the
// yardstick's targets hold its last draws, which must be the pass without the classification
// (so without the fallback) and the least lookup.
TEST_F(PassBench, EsmsTwoCameraRowsTimeWhatTheyName) {
  gl::Renderer renderer(*context);
  gl::RenderSettings s = small(Technique::Esm);
  s.shadowMapSize = 512;
  s.width = 160;
  s.height = 90;
  s.filter = gl::FilterMode::Bilinear;
  const Scene scene = makeBuiltinScene("backyard");
  const gl::PassBenchResult r = gl::benchPasses(renderer, scene, s, 1);
  // encode, prefilter, camera (no mips: bilinear)
  ASSERT_EQ(r.passes[3].pass, "camera, classification off");
  const int drawsPerRow = 1 + gl::kCameraDrawsPerFrame;  // the warm-up, then one frame's
  EXPECT_EQ(renderer.minimalLookupDraws(true), drawsPerRow);
  EXPECT_EQ(renderer.minimalLookupDraws(false), drawsPerRow);
  const Image pass = renderer.readCameraColor();
  const Image yardstick = renderer.readMinimalLookupColor();
  const auto same = [](const Image& a, const Image& b) {
    return std::ranges::equal(a.data(), b.data());
  };
  gl::RenderSettings unclassified = s;
  unclassified.params.esm.classifier = shaders::kEsmClassifyNone;
  unclassified.readBack = gl::frame_image::kColor;
  s.readBack = gl::frame_image::kColor;
  const gl::RenderResult classifiedFrame = renderer.render(scene, s);
  renderer.timeMinimalLookup(true);
  const Image withFallback = renderer.readMinimalLookupColor();
  EXPECT_FALSE(same(pass, classifiedFrame.color)) << "the view must show ESM's fallback";
  EXPECT_FALSE(same(yardstick, withFallback));
  EXPECT_TRUE(same(pass, renderer.render(scene, unclassified).color));
  renderer.timeMinimalLookup(false);
  EXPECT_TRUE(same(yardstick, renderer.readMinimalLookupColor()));
}

// The bench times the camera pass several times a frame (kCameraDrawsPerFrame): the draws after
// the frame's own must be the production pass again, not a cheaper one nor none.
TEST_F(PassBench, TheCameraPassDrawnAgainIsTheFramesOwn) {
  gl::Renderer renderer(*context);
  const Scene scene = makeBuiltinScene("backyard");
  EXPECT_THROW(renderer.timeCameraPass(), Error);  // no frame yet
  gl::RenderSettings s = small(Technique::Esm);
  s.shadowMapSize = 512;
  s.width = 160;
  s.height = 90;
  s.filter = gl::FilterMode::Bilinear;
  s.readBack = gl::frame_image::kColor;
  const gl::RenderResult frame = renderer.render(scene, s);
  // What the draw rasterised: the frame's geometry again, depth-tested, covering the view but
  // its sky (a draw that drew nothing counts 0).
  GLuint query = 0;
  glGenQueries(1, &query);
  glBeginQuery(GL_SAMPLES_PASSED, query);
  EXPECT_GT(renderer.timeCameraPass(), 0.0);
  glEndQuery(GL_SAMPLES_PASSED);
  GLuint samples = 0;
  glGetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
  glDeleteQueries(1, &query);
  EXPECT_GT(samples, GLuint(s.width * s.height / 2));
  // ESM's picture, fallback and all, bit for bit, in the camera pass's own target: the
  // reference's variant, which draws the filtered reference, or another technique's would
  // differ.
  EXPECT_TRUE(std::ranges::equal(renderer.readCameraColor().data(), frame.color.data()));
  // Frames whose camera pass is not a technique's: a reference's, the CPU-given depth map's.
  renderer.renderReference(scene, s, 1);
  EXPECT_THROW(renderer.timeCameraPass(), Error);
  renderer.render(scene, s);
  renderer.filterDepthMap(renderer.readDepthMap(), s);
  EXPECT_THROW(renderer.timeCameraPass(), Error);
}

// The bench dispatches the encode several times a frame (kEncodeDispatchesPerFrame): the
// dispatches after the frame's own must be its encode again, of the frame's depth, into the
// channels it filtered (level 0 then holds them unblurred), not a cheaper pass nor none.
TEST_F(PassBench, TheEncodeDispatchedAgainIsTheFramesOwn) {
  gl::Renderer renderer(*context);
  EXPECT_THROW(renderer.timeEncodePass(), Error);  // nothing filtered yet
  Image depth(64, 64, 1);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) depth.at(x, y) = 0.2f + 0.05f * float((7 * x + 3 * y) % 13);
  }
  gl::RenderSettings s = small(Technique::Csm);  // the row the repeated dispatches are for
  s.filter = gl::FilterMode::Bilinear;
  s.params.csm.storage = shaders::kStorageFloat32;
  s.blur = BlurSpec{BlurKernel::Box, 2, 1.0f};
  renderer.filterDepthMap(depth, s);
  const Image blurred = renderer.readChannels(0);
  EXPECT_GT(renderer.timeEncodePass(), 0.0);
  const Image again = renderer.readChannels(0);
  gl::RenderSettings unblurred = s;
  unblurred.blur.radius = 0;
  renderer.filterDepthMap(depth, unblurred);
  const Image encoded = renderer.readChannels(0);
  EXPECT_FALSE(std::ranges::equal(blurred.data(), encoded.data()));  // the blur shows
  EXPECT_TRUE(std::ranges::equal(again.data(), encoded.data()));
  // The fused path has no encode of its own to dispatch.
  s.fusePrefilter = true;
  renderer.filterDepthMap(depth, s);
  EXPECT_THROW(renderer.timeEncodePass(), Error);
}

TEST_F(PassBench, TechniquesWithoutAPrefilterAreRefused) {
  gl::Renderer renderer(*context);
  for (Technique t : {Technique::Pcf, Technique::Hard}) {
    try {
      gl::benchPasses(renderer, makeBuiltinScene("planar"), small(t), 1);
      ADD_FAILURE() << techniqueId(t) << " must be refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("no prefilter"), std::string::npos) << e.what();
    }
    // Their frame has neither an encode to repeat nor channels for a minimal lookup to fetch
    // (it would draw every pixel from an empty unit).
    renderer.render(makeBuiltinScene("planar"), small(t));
    EXPECT_THROW(renderer.timeEncodePass(), Error) << techniqueId(t);
    EXPECT_THROW(renderer.timeMinimalLookup(), Error) << techniqueId(t);
  }
}

}  // namespace
}  // namespace penumbra
