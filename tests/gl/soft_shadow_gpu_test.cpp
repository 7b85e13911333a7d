// Soft shadows on the GPU: the area-light reference against the analytic penumbra of a disk
// light and of a sphere light over a straight edge, and its convergence as the light's sample
// count grows; the renderer's soft lookups (PCSS and the filterable techniques' widened filters)
// against the CPU twin running the same shared code, for a spot-like disk and a point light's
// sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "../common/edge_scenes.h"
#include "gl_test_context.h"
#include "penumbra/area_light.h"
#include "penumbra/error.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/params.h"
#include "penumbra/shadow_lookup.h"
#include "penumbra/shared/soft_shadow.h"

namespace penumbra {
namespace {

struct EdgeErrors {
  double rmse = 0.0;
  double maxAbsolute = 0.0;
  int pixels = 0;
};

class SoftShadowGpu : public testing::GlTest {};

template <typename Analytic>
EdgeErrors edgeErrors(gl::Renderer& renderer, const Scene& scene, int samples, int mapSize,
                      float halfBand, Analytic analytic) {
  gl::RenderSettings s;
  s.lookupInputs = true;  // the test reads the lookup's inputs
  s.shadowMapSize = mapSize;
  s.width = 96;
  s.height = 64;
  renderer.setScene(scene);
  const gl::RenderResult r =
      renderer.renderAreaLightReference(s, gl::FrameView{scene.camera, scene.light}, samples, 1);
  const glm::mat4 worldFromClip = glm::inverse(
      clipFromView(scene.camera, float(s.width) / float(s.height), scene.viewBounds()) *
      viewFromWorld(scene.camera));
  EdgeErrors e;
  double sum = 0.0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      if (r.lookup.at(x, y, 3) < 1.0f) continue;  // lit-facing surfaces inside the map
      const glm::vec2 ndc((float(x) + 0.5f) / float(s.width) * 2.0f - 1.0f,
                          1.0f - (float(y) + 0.5f) / float(s.height) * 2.0f);
      const glm::vec4 a = worldFromClip * glm::vec4(ndc, -1.0f, 1.0f);
      const glm::vec4 b = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
      const glm::vec3 near = glm::vec3(a) / a.w, far = glm::vec3(b) / b.w;
      const glm::vec3 ground = near + (far - near) * (near.y / (near.y - far.y));
      // The penumbra and some of the umbra and light around it, away from the plate's other
      // edges.
      if (std::abs(ground.x) > halfBand || std::abs(ground.z) > 1.2f) continue;
      const double error = double(r.visibility.at(x, y)) - analytic(ground);
      sum += error * error;
      e.maxAbsolute = std::max(e.maxAbsolute, std::abs(error));
      ++e.pixels;
    }
  }
  e.rmse = std::sqrt(sum / std::max(e.pixels, 1));
  return e;
}

TEST_F(SoftShadowGpu, AreaLightReferenceEqualsTheAnalyticDiskPenumbraAndConvergesWithSamples) {
  gl::Renderer renderer(*context);
  const Scene scene = edgeScene();
  // 1024 texels: 71 across the penumbra (|x| < 0.125).
  const auto analytic = [](glm::vec3 ground) { return analyticDiskEdgeVisibility(ground.x); };
  const EdgeErrors coarse = edgeErrors(renderer, scene, 64, 1024, 0.2f, analytic);
  const EdgeErrors fine = edgeErrors(renderer, scene, 256, 1024, 0.2f, analytic);
  std::printf(
      "area-light reference vs analytic disk-edge penumbra: 64 samples RMSE %.4f max "
      "%.4f, 256 samples RMSE %.4f max %.4f (%d pixels)\n",
      coarse.rmse, coarse.maxAbsolute, fine.rmse, fine.maxAbsolute, fine.pixels);
  ASSERT_GT(fine.pixels, 300);  // the penumbra's neighbourhood fills a band of the frame
  // A straight chord crosses at most about 2 side cells of the side x side stratified grid, each
  // off by at most 1/N: max error <= 2 side / N = 2 / side (0.25 for 64 samples, 0.125 for
  // 256); the map's texels move the edge by up to half a texel (1/140 of the penumbra), 0.005
  // of visibility at the steepest.
  EXPECT_LT(coarse.maxAbsolute, 0.25 + 0.005);
  // Those cells' errors are independent, each within 1/N: RMSE <= sqrt(2 side) / N (0.0625).
  EXPECT_LT(coarse.rmse, std::sqrt(16.0) / 64.0);
  EXPECT_LT(fine.maxAbsolute, 0.125 + 0.005);
  // Converges: the RMSE falls with the samples (stratified sampling of an edge: as N^-3/4,
  // 2.8x from 64 to 256; asked for 2x). Measured on llvmpipe: 0.0225 (64), 0.0033 (1024).
  EXPECT_LT(fine.rmse, 0.5 * coarse.rmse);
}

TEST_F(SoftShadowGpu, SphereLightReferenceEqualsTheAnalyticPenumbraAndConvergesWithSamples) {
  gl::Renderer renderer(*context);
  const Scene scene = sphereEdgeScene();
  // 512 texels: a texel 0.004 wide at the plate (distance 1), the penumbra (|x| < 0.25 on the
  // ground) 64 texels across.
  const auto analytic = [](glm::vec3 ground) { return analyticSphereEdgeVisibility(ground); };
  const EdgeErrors coarse = edgeErrors(renderer, scene, 64, 512, 0.35f, analytic);
  const EdgeErrors fine = edgeErrors(renderer, scene, 256, 512, 0.35f, analytic);
  std::printf(
      "sphere-light reference vs analytic sphere-edge penumbra: 64 samples RMSE %.4f max %.4f, "
      "256 samples RMSE %.4f max %.4f (%d pixels)\n",
      coarse.rmse, coarse.maxAbsolute, fine.rmse, fine.maxAbsolute, fine.pixels);
  ASSERT_GT(fine.pixels, 300);
  // Converges like the disk's stratified estimate: measured on llvmpipe RMSE 0.0605 (64
  // samples), 0.0253 (256), 0.0107 (1024; the same 0.0255 for 256 samples with a 1024 map: the
  // samples, not the texels, set the error), about N^-0.63, so a 4x count at least halves it.
  // Bounds at 1.3x the measured RMSE (another rasteriser moves the edge by a fraction of a
  // texel). The plain mean of the samples (no solid-angle weight: uniform over the sphere's
  // area, the silhouette's rim over-weighted) stalls at 0.0479 and 0.0368 and fails both.
  EXPECT_LT(coarse.rmse, 1.3 * 0.0605);
  EXPECT_LT(fine.rmse, 1.3 * 0.0253);
  EXPECT_LT(fine.rmse, 0.5 * coarse.rmse);
}

// The sphere light's receivers come from the centre frame's lookup and cascades whatever the
// caller reads back or times: a reference that reads only its visibility, or is not timed, has
// the same visibility. Its wall times sum its samples' frames: absent (not 0) when untimed.
TEST_F(SoftShadowGpu, ASphereLightReferenceReadingLessOrUntimedWeighsItsSamplesTheSame) {
  gl::Renderer renderer(*context);
  const Scene scene = sphereEdgeScene();
  gl::RenderSettings s;
  s.shadowMapSize = 256;
  s.width = 48;
  s.height = 32;
  renderer.setScene(scene);
  const gl::FrameView view{scene.camera, scene.light};
  const Image all = renderer.renderAreaLightReference(s, view, 64, 1).visibility;
  s.readBack = gl::frame_image::kVisibility;
  const gl::RenderResult lean = renderer.renderAreaLightReference(s, view, 64, 1);
  EXPECT_TRUE(lean.lookup.empty());
  // GPU times only where every sample's frame has them (none on llvmpipe).
  EXPECT_EQ(lean.gpuTimes.has_value(), renderer.timerQueriesMeasureExecution());
  // The same frames and sums: equal to the last bit.
  EXPECT_TRUE(std::ranges::equal(lean.visibility.data(), all.data()));
  ASSERT_TRUE(lean.wallTimes.has_value());
  EXPECT_GT(lean.wallTimes->camera, 0.0);
  s.timing = false;
  const gl::RenderResult untimed = renderer.renderAreaLightReference(s, view, 64, 1);
  EXPECT_FALSE(untimed.wallTimes.has_value());
  EXPECT_FALSE(untimed.gpuTimes.has_value());
  EXPECT_TRUE(std::ranges::equal(untimed.visibility.data(), all.data()));
}

// Every pixel's |GPU - CPU| under a soft light. LookupParity holds each pixel to an envelope
// derived from the twin's filtered channels, but CpuShadowLookup::filteredChannels does not
// model the soft probes, so this bound is not derived: it is the largest difference on these
// frames (8.5e-3, MSM with summed-area tables, where one unorm16 step of the moments moves the
// Hamburger solve most) rounded up. It still fails a lookup that reads the wrong texel or probe.
constexpr float kSoftMaxRounding = 1e-2f;

TEST_F(SoftShadowGpu, SoftPointLightLookupsEqualTheCpuTwinFaceByFace) {
  gl::Renderer renderer(*context);
  Scene scene = makeBuiltinScene("lantern");
  scene.light.size = 0.3f;  // penumbrae of ~10 texels on the walls of a 256 map
  struct Case {
    Technique technique;
    FilterMode filter;
  };
  for (const Case c :
       {Case{Technique::Pcf, FilterMode::Point}, Case{Technique::Vsm, FilterMode::Trilinear},
        Case{Technique::Msm, FilterMode::SummedArea}}) {
    gl::RenderSettings s;
    s.lookupInputs = true;  // the test reads the lookup's inputs
    s.technique = c.technique;
    s.filter = c.filter;
    s.shadowMapSize = 256;
    s.width = 96;
    s.height = 96;
    s.blur = {BlurKernel::Box, 1, 1.0f};
    const gl::RenderResult r = renderer.render(scene, s);
    const LightView& view = r.cascadeFrame.light;  // the faces' projection, guard band included
    LookupConfig config{c.technique, r.params,     c.filter,
                        s.blur,      s.anisotropy, renderer.halfFloatRounding()};
    config.softLight = {scene.light.size,
                        1,
                        view.nearDistance,
                        view.farDistance,
                        view.texelWorldSize(s.shadowMapSize),
                        shaders::pointLightSoftWidthTexels(s.shadowMapSize)};
    std::map<int, std::unique_ptr<CpuShadowLookup>> twins;
    std::vector<float> errors;
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        if (r.lookup.at(x, y, 3) <= 0.0f) continue;
        const int face = int(r.cascades.at(x, y, 0));
        std::unique_ptr<CpuShadowLookup>& twin = twins[face];
        if (!twin) twin = std::make_unique<CpuShadowLookup>(renderer.readDepthMap(face), config);
        errors.push_back(
            std::abs(twin->lookup(gl::lookupPixelAt(r, x, y)).visibility - r.visibility.at(x, y)));
      }
    }
    std::sort(errors.begin(), errors.end());
    ASSERT_GT(errors.size(), 3000u);
    ASSERT_EQ(twins.size(), 6u) << "the view must see every face";
    const float p99 = errors[size_t(0.99 * double(errors.size()))];
    std::printf("point %s %s: %zu pixels, p99 %.2e, max %.2e\n",
                std::string(techniqueId(c.technique)).c_str(),
                std::string(filterModeName(c.filter)).c_str(), errors.size(), p99, errors.back());
    if (c.technique == Technique::Pcf) {
      // PCSS reads texels and weights them in the same order on both sides: equal to the bit.
      EXPECT_EQ(errors.back(), 0.0f);
    } else {
      // As for the disk lights above: rounding only, 99% of pixels within 2e-3, every one
      // within kSoftMaxRounding.
      EXPECT_LT(p99, 2e-3f) << techniqueId(c.technique);
      EXPECT_LE(errors.back(), kSoftMaxRounding) << techniqueId(c.technique);
    }
  }
}

TEST_F(SoftShadowGpu, SoftLookupsEqualTheCpuTwinOnThePenumbraeScene) {
  gl::Renderer renderer(*context);
  Scene scene = makeBuiltinScene("penumbrae");
  scene.light.size = 0.3f;  // penumbrae wider than the pixels: the probes decide
  const LightView view = fitLightView(scene);
  struct Case {
    Technique technique;
    FilterMode filter;
  };
  for (const Case c :
       {Case{Technique::Pcf, FilterMode::Point}, Case{Technique::Vsm, FilterMode::Trilinear},
        Case{Technique::Evsm4, FilterMode::Trilinear},
        Case{Technique::Msm, FilterMode::SummedArea}}) {
    gl::RenderSettings s;
    s.lookupInputs = true;  // the test reads the lookup's inputs
    s.technique = c.technique;
    s.filter = c.filter;
    s.shadowMapSize = 256;
    s.width = 96;
    s.height = 54;
    s.blur = {BlurKernel::Box, 1, 1.0f};
    const gl::RenderResult r = renderer.render(scene, s);
    LookupConfig config{c.technique, r.params,     c.filter,
                        s.blur,      s.anisotropy, renderer.halfFloatRounding()};
    config.softLight = {scene.light.size,
                        0,
                        view.nearDistance,
                        view.farDistance,
                        view.texelWorldSize(s.shadowMapSize),
                        shaders::kMaxSoftWidthTexels};
    const CpuShadowLookup twin(renderer.readDepthMap(), config);
    std::vector<float> errors;
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        if (r.lookup.at(x, y, 3) <= 0.0f) continue;
        errors.push_back(
            std::abs(twin.lookup(gl::lookupPixelAt(r, x, y)).visibility - r.visibility.at(x, y)));
      }
    }
    std::sort(errors.begin(), errors.end());
    ASSERT_GT(errors.size(), 1000u);
    const float p99 = errors[size_t(0.99 * double(errors.size()))];
    std::printf("%s %s: %zu pixels, p99 %.2e, max %.2e\n",
                std::string(techniqueId(c.technique)).c_str(),
                std::string(filterModeName(c.filter)).c_str(), errors.size(), p99, errors.back());
    // Both sides run shared/soft_shadow.h; only rounding differs (fp32 in another order, the
    // texture unit's 8-bit filter weights for trilinear lookups): 99% of pixels within 2e-3, the
    // rest where a search or filter tap rounds to the neighbouring texel, every one within
    // kSoftMaxRounding.
    EXPECT_LT(p99, 2e-3f) << techniqueId(c.technique);
    EXPECT_LE(errors.back(), kSoftMaxRounding) << techniqueId(c.technique);
  }
}

}  // namespace
}  // namespace penumbra
