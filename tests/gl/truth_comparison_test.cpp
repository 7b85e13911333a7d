// compare against the ray-traced truth: the truth does not depend on the shadow map while the
// references converge to it; only silhouettes are left out of the same-surface match; on a
// curved real model the filtered reference's own darkening shows in the decomposition, PCF gets a
// real error, and the ranking follows the truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "gl_test_context.h"
#include "penumbra/compare/comparison.h"
#include "penumbra/compare/report.h"
#include "penumbra/error.h"
#include "penumbra/metrics.h"
#include "penumbra/truth/true_shadow.h"

namespace penumbra {
namespace {

// A real curved model (Debian's assimp-testmodels): 3,732 triangles, low-poly, lit from above.
constexpr const char* kWuson = "/usr/share/assimp/models/OBJ/WusonOBJ.obj";

class TruthComparison : public testing::GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (context) renderer = std::make_unique<gl::Renderer>(*context);
  }

  static compare::ComparisonRequest request(const std::string& scene,
                                            std::vector<Technique> techniques) {
    compare::ComparisonRequest r;
    r.scene = scene;
    r.techniques = std::move(techniques);
    r.settings.shadowMapSize = 512;
    r.settings.width = 200;
    r.settings.height = 112;
    r.settings.blur = {BlurKernel::Box, 2, 1.0f};  // compare's 5-tap box
    r.settings.filter = gl::FilterMode::Bilinear;
    r.supersample = 2;
    r.pathFrames = 2;
    return r;
  }

  static const compare::TechniqueResult& find(const compare::ComparisonResult& r, Technique t) {
    for (const auto& k : r.techniques) {
      if (k.technique == t) return k;
    }
    throw Error("missing technique");
  }

  std::unique_ptr<gl::Renderer> renderer;
};

TEST_F(TruthComparison, TheTruthIsTheSameWhateverTheShadowMapAndTheReferencesConvergeToIt) {
  compare::ComparisonRequest q = request("backyard", {Technique::Hard});
  q.settings.shadowMapSize = 256;
  const compare::ComparisonResult coarse = compare::runComparison(q, *renderer);
  q.settings.shadowMapSize = 2048;
  const compare::ComparisonResult fine = compare::runComparison(q, *renderer);
  ASSERT_TRUE(coarse.truth && fine.truth);
  const Image& a = coarse.truth->visibility;
  const Image& b = fine.truth->visibility;
  ASSERT_EQ(a.data().size(), b.data().size());
  EXPECT_EQ(std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)), 0)
      << "the truth changed with the shadow map";
  // The shadow map did change the references, and they move towards the truth: the sampling
  // part of every technique's error shrinks as the map grows (measured 0.13 -> 0.06 at 200 x 112,
  // 2 x 2 sub-pixels, 5-tap box). 0.75x: 8x the texels must at least take a quarter of it off.
  EXPECT_GT(coarse.truth->referenceVsTruth.rmse, 0.0);
  EXPECT_LT(fine.truth->referenceVsTruth.rmse, 0.75 * coarse.truth->referenceVsTruth.rmse);
  EXPECT_LT(fine.truth->groundTruthVsTruth.rmse, 0.75 * coarse.truth->groundTruthVsTruth.rmse);
  // So does the hard test, whose error against the truth is its resolution alone.
  EXPECT_LT(find(fine, Technique::Hard).truth->rmse,
            0.75 * find(coarse, Technique::Hard).truth->rmse);
}

// Backyard near the camera, and 2CylinderEngine (assimp-testmodels) framed from 900 units away: with
// the near plane fixed at 0.05 the depth buffer resolved its view depth only to 1e-3, and the
// match left 90% of its lit faces out (cameraNear now scales with the scene).
TEST_F(TruthComparison, OnlySilhouettesAreLeftOutOfTheSameSurfaceMatch) {
  Scene engine = loadScene(
      "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  engine.camera.verticalFovDegrees = 20.0f;
  for (const Scene& scene : {makeBuiltinScene("backyard"), engine}) {
    SCOPED_TRACE(scene.name);
    gl::RenderSettings s;
    s.width = 160;
    s.height = 90;
    s.shadowMapSize = 512;
    const int S = 2;
    renderer->setScene(scene);
    renderer->renderReference(s, gl::FrameView{scene.camera, scene.light}, S);
    const Image depth = renderer->readCameraDepth();
    truth::TrueShadowRequest t;
    t.camera = scene.camera;
    t.light = scene.light;
    t.viewBounds = scene.viewBounds();
    t.width = s.width;
    t.height = s.height;
    t.supersample = S;
    const truth::RayScene rays(scene);
    const truth::TrueShadow traced = truth::traceTrueShadow(rays, t);
    const truth::SurfaceMatch match = truth::matchRasterisedSurfaces(traced, depth, t);
    // Every excluded pixel straddles a depth discontinuity: some pair of neighbouring
    // rasterised sub-pixels around it differs by more than 0.5% in view depth (or one sees
    // nothing) — five times the match's tolerance; the engine's stacked fins step by about 1%.
    const glm::mat4 projection =
        clipFromView(scene.camera, float(s.width) / float(s.height), scene.viewBounds());
    auto viewDepth = [&](int x, int y) {
      const float w = depth.at(std::clamp(x, 0, depth.width() - 1),
                               std::clamp(y, 0, depth.height() - 1));
      if (!(w < 1.0f)) return 1e30;
      return double(projection[3][2]) / (2.0 * double(w) - 1.0 + double(projection[2][2]));
    };
    int notAtAnEdge = 0;
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        if (match.matched.at(x, y) > 0.5f) continue;
        double lo = 1e30, hi = 0.0;
        for (int sy = -1; sy <= S; ++sy) {
          for (int sx = -1; sx <= S; ++sx) {
            const double d = viewDepth(x * S + sx, y * S + sy);
            lo = std::min(lo, d);
            hi = std::max(hi, d);
          }
        }
        if (!(hi > 1.005 * lo)) ++notAtAnEdge;
      }
    }
    int drawn = 0;
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) drawn += traced.visibility.at(x, y) >= 0.0f ? 1 : 0;
    }
    std::printf("%s: %d of %d drawn pixels left out\n", scene.name.c_str(), match.excludedPixels,
                drawn);
    EXPECT_GT(match.excludedPixels, 0);  // both have silhouettes
    EXPECT_LT(match.excludedPixels, drawn / 10);
    EXPECT_EQ(notAtAnEdge, 0);
    // A rasterised frame one sub-pixel row off sees other surfaces along every edge: the match
    // notices (measured on backyard: about 10x the silhouette pixels).
    Image shifted = depth;
    for (int y = 0; y < depth.height(); ++y) {
      for (int x = 0; x < depth.width(); ++x) shifted.at(x, y) = depth.at(x, std::max(y - 1, 0));
    }
    EXPECT_GT(truth::matchRasterisedSurfaces(traced, shifted, t).excludedPixels,
              3 * match.excludedPixels);
  }
}

TEST_F(TruthComparison, OnACurvedModelTheReferencesOwnDarkeningIsSeparatedFromTheTechniques) {
  compare::ComparisonRequest q = request(kWuson, {Technique::Hard, Technique::Pcf, Technique::Vsm});
  q.view.cameraFovDegrees = 14.0f;  // the model fills the frame
  q.settings.shadowMapSize = 1024;
  q.settings.width = 320;
  q.settings.height = 180;
  const compare::ComparisonResult r = compare::runComparison(q, *renderer);
  ASSERT_TRUE(r.truth);
  const compare::TruthResult& t = *r.truth;
  std::printf("Wuson: %d pixels measured, %d silhouette, %d unlit, %d where the reference "
              "darkens a lit truth; reference vs truth RMSE %.4f dark share %.4f\n",
              t.referenceVsTruth.pixels, t.excludedPixels, t.unlitPixels,
              t.referenceTooDarkPixels, t.referenceVsTruth.rmse, t.referenceVsTruth.darkShare);
  ASSERT_GT(t.referenceVsTruth.pixels, 10000);
  // The sampling part: the filtered reference's receiver plane, extended over its kernel, lies
  // behind the neighbouring triangles of the convex body, so it darkens lit surfaces along
  // triangle edges (measured at 640 x 360: dark share 0.19, RMSE 0.13).
  EXPECT_GT(t.referenceVsTruth.darkShare, 0.08);
  EXPECT_GT(t.referenceTooDarkPixels, t.referenceVsTruth.pixels / 20);
  // The low-poly body's terminator is left out (unlit), not scored.
  EXPECT_GT(t.unlitPixels, 0);

  const compare::TechniqueResult& pcf = find(r, Technique::Pcf);
  const compare::TechniqueResult& vsm = find(r, Technique::Vsm);
  const compare::TechniqueResult& hard = find(r, Technique::Hard);
  // Matched PCF is the filtered reference (its error against it is rounding), and against the
  // truth it now has the reference's own error.
  EXPECT_LT(pcf.filtered.rmse, 1e-5);
  ASSERT_TRUE(pcf.truth && vsm.truth && hard.truth);
  EXPECT_NEAR(pcf.truth->rmse, t.referenceVsTruth.rmse, 1e-6);
  // The ranking follows the truth: the hard test and VSM, which do not darken the body, beat
  // the reference's PCF (measured 0.04 and 0.05 against 0.13).
  const std::vector<const compare::TechniqueResult*> ranked = compare::rankTechniques(r);
  EXPECT_EQ(ranked.back()->technique, Technique::Pcf);
  EXPECT_LT(vsm.truth->rmse, 0.6 * pcf.truth->rmse);
  // Against the truth VSM barely leaks (measured 0.018); against the reference it would be
  // called leaking wherever the reference darkens the lit body, and those pixels are left out
  // of its leak columns.
  EXPECT_LT(vsm.truth->leakShare, 0.04);
  const VisibilityErrors everywhere =
      measureVisibilityErrors(vsm.visibility, r.referenceVisibility, r.coverage, q.tau);
  std::printf("VSM leak share against the reference: %.4f reported, %.4f counting the "
              "reference's darkened pixels\n",
              vsm.filtered.leakShare, everywhere.leakShare);
  EXPECT_LT(vsm.filtered.leakShare, everywhere.leakShare - 0.03);
}

// The camera pass is compiled per light kind (LIGHT_PERSPECTIVE, POINT_LIGHT, CASCADED): a spot
// light's, a point light's and a directional light's cascades each put their hard shadows where
// the ray tracer does. The lookup-parity tests cannot see this: the CPU twin replays the
// receiver depth and uv the GPU wrote, right or wrong.
TEST_F(TruthComparison, EveryLightKindsHardShadowsFollowTheTruth) {
  struct Case {
    const char* scene;
    int cascades;
  };
  for (const Case c : {Case{"spheres", 1}, Case{"lantern", 1}, Case{"backyard", 3}}) {
    SCOPED_TRACE(c.scene);
    compare::ComparisonRequest q = request(c.scene, {Technique::Hard});
    q.settings.shadowMapSize = 1024;
    q.settings.cascades.count = c.cascades;
    const compare::ComparisonResult r = compare::runComparison(q, *renderer);
    ASSERT_TRUE(r.truth);
    const double rmse = find(r, Technique::Hard).truth->rmse;
    std::printf("%s, %d cascade(s): hard vs truth RMSE %.4f\n", c.scene, c.cascades, rmse);
    // A hard test at 1024² errs at shadow edges only (measured 0.034-0.063 at these sizes); a light
    // kind compiled wrong moves or loses whole shadows (a spot light taken as directional lit
    // nothing inside its map; see the closing note of issue 28 for the mutations tried).
    EXPECT_LT(rmse, 0.1);
  }
}

}  // namespace
}  // namespace penumbra
