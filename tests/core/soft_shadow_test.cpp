// Soft shadows on the CPU twin (the same shared code as the GPU, shared/soft_shadow.h): PCSS's
// penumbra grows with the receiver-blocker distance as Fernando's formula says, every
// technique's soft variant is a visibility (in [0,1], finite) and lit where nothing occludes;
// and the area light's point samples (penumbra/area_light.h) cover the disk evenly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <random>

#include "penumbra/area_light.h"
#include "penumbra/error.h"
#include "penumbra/params.h"
#include "penumbra/shadow_lookup.h"
#include "penumbra/shared/shadow_lookup.h"

namespace penumbra {
namespace {

constexpr int kMapSize = 256;
constexpr int kEdge = 128;  // blocker texels x < kEdge

// A half-plane blocker at `blocker` over a flat receiver at `receiver` (the map holds the
// receiver where nothing blocks it).
Image halfPlaneBlocker(float blocker, float receiver) {
  Image depth(kMapSize, kMapSize, 1);
  for (int y = 0; y < kMapSize; ++y) {
    for (int x = 0; x < kMapSize; ++x) depth.at(x, y) = x < kEdge ? blocker : receiver;
  }
  return depth;
}

// Linear depth over [near, far] world units; texel world size `texel` (at unit distance: spot).
shaders::SoftLight softLight(float size, bool perspective, float near, float far, float texel) {
  return {size, perspective ? 1 : 0, near, far, texel, shaders::kMaxSoftWidthTexels};
}

LookupConfig softConfig(Technique technique, FilterMode filter, shaders::SoftLight light) {
  LookupConfig config;
  config.technique = technique;
  config.params = defaultTechniqueParams();
  config.filter = filter;
  config.blur = {BlurKernel::Box, 0, 1.0f};
  config.softLight = light;
  return config;
}

// The penumbra's width in texels measured from a visibility profile v(x) across the edge:
// 6 x integral of v (1 - v), which is exactly the width of a linear ramp (integral W / 6) and
// within 2% of it for PCSS's 8-step staircase of tents (1.3125 W / 8 = W / 6.1).
double measuredPenumbraTexels(const CpuShadowLookup& lookup, float receiver) {
  double integral = 0.0;
  const double step = 0.125;  // texels: fine against the tents' width of 1
  for (double x = 0.0; x < double(kMapSize); x += step) {
    LookupPixel p;
    p.uv = {float(x / kMapSize), 0.5f};
    p.receiverDepth = receiver;
    const double v = lookup.lookup(p).visibility;
    integral += v * (1.0 - v) * step;
  }
  return 6.0 * integral;
}

TEST(Pcss, PenumbraWidthGrowsWithTheReceiverBlockerDistanceAsItsFormulaSays) {
  // Directional light of angular size 0.05 over [10, 30] world units, 0.02-unit texels; the
  // blocker at distance 12. Fernando's similar triangles for a light at infinity:
  // w = size (z_r - z_b), in texels w / texel.
  const float near = 10.0f, far = 30.0f, texel = 0.02f, size = 0.05f;
  const float blocker = 12.0f;
  double previous = 0.0;
  for (float receiver : {13.0f, 15.0f, 18.0f}) {
    const float dBlocker = (blocker - near) / (far - near);
    const float dReceiver = (receiver - near) / (far - near);
    const CpuShadowLookup lookup(
        halfPlaneBlocker(dBlocker, dReceiver),
        softConfig(Technique::Pcf, FilterMode::Point, softLight(size, false, near, far, texel)));
    const double expected = size * (receiver - blocker) / texel;  // 2.5, 7.5, 15 texels
    const double measured = measuredPenumbraTexels(lookup, dReceiver);
    // The bilinear tent under each tap widens the ramp by about 1/6 texel^2 / W and the 8-step
    // staircase narrows it by 2%: within 5% + 0.5 texel.
    EXPECT_NEAR(measured, expected, 0.05 * expected + 0.5) << "receiver at " << receiver;
    EXPECT_GT(measured, previous);
    previous = measured;
  }
}

TEST(Pcss, SpotLightPenumbraFollowsThePerspectiveFormula) {
  // A disk of diameter 0.5 at the light; blocker at 4, receivers at 6 and 8 world units; texel
  // 0.002 at unit distance. w = size (z_r - z_b) / z_b world units at the receiver, where a texel
  // is 0.002 z_r wide.
  const float near = 2.0f, far = 12.0f, texelAtUnit = 0.002f, size = 0.5f, blocker = 4.0f;
  for (float receiver : {6.0f, 8.0f}) {
    const float dBlocker = (blocker - near) / (far - near);
    const float dReceiver = (receiver - near) / (far - near);
    const CpuShadowLookup lookup(halfPlaneBlocker(dBlocker, dReceiver),
                                 softConfig(Technique::Pcf, FilterMode::Point,
                                            softLight(size, true, near, far, texelAtUnit)));
    const double expected =
        size * (receiver - blocker) / blocker / (texelAtUnit * receiver);  // 20.8, 31.3
    EXPECT_NEAR(measuredPenumbraTexels(lookup, dReceiver), expected, 0.05 * expected + 0.5)
        << "receiver at " << receiver;
  }
}

TEST(SoftShadows, FilterableWidthMatchesPcssInTheMean) {
  // A filterable technique over the same edge: its mip probes (soft_shadow.h) follow the same
  // blocker estimate, and their kernel (4 x 4 probes of 2^lod blocks under the bilinear tent) has
  // the second moment of PCSS's box. VSM is exact over a two-depth edge (Chebyshev's bound is tight
  // for two depths, thesis §3.2), so its profile is the filter's. Mip blocks are aligned to the
  // map, so the width depends on where the edge falls in a block: averaged over the 16 phases of
  // the coarsest level used (lod 3.1: 8- and 16-texel blocks).
  const float near = 10.0f, far = 30.0f, texel = 0.02f, size = 0.05f;
  const float dBlocker = 0.1f, dReceiver = 0.4f;  // 12 and 18 world units: 15 texels
  const shaders::SoftLight light = softLight(size, false, near, far, texel);
  // No prefilter, and a 9-tap box blur (variance 20/3 texels^2) whose share the probes leave
  // out: the penumbra is the box's either way (stacked, the two would make it 17.5 texels wide).
  for (int blurRadius : {0, 4}) {
    double mean = 0.0;
    for (int phase = 0; phase < 16; ++phase) {
      Image depth(kMapSize, kMapSize, 1);
      for (int y = 0; y < kMapSize; ++y) {
        for (int x = 0; x < kMapSize; ++x) depth.at(x, y) = x < 120 + phase ? dBlocker : dReceiver;
      }
      LookupConfig config = softConfig(Technique::Vsm, FilterMode::Trilinear, light);
      config.blur.radius = blurRadius;
      const CpuShadowLookup vsm(depth, config);
      mean += measuredPenumbraTexels(vsm, dReceiver) / 16.0;
    }
    // The probes' kernels blend two mip levels linearly in lod, not in variance: their width is
    // off by up to 6% between levels. Measured on the CPU twin: 15.03.
    EXPECT_NEAR(mean, 15.0, 0.1 * 15.0) << "blur radius " << blurRadius;
  }
}

TEST(SoftShadows, EsmFallbackUnderAnAreaLightIsPcssOverThePenumbra) {
  // A receiver at 20 world units inside the shadow of an occluder at 16 whose edge lies two texels
  // away, with open ground at 28 beyond it: the ground behind the receiver dominates ESM's
  // filtered exp(c z) (ESM paper §3.3), so the pixel fails classification. Its penumbra is
  // 0.05 x (20 - 16) / 0.02 = 10 texels, a share of which sees past the edge. The fallback once
  // tested the blur's own kernel, 2x2 texels with no blur: a hard 0 inside a soft penumbra.
  const float near = 10.0f, far = 30.0f, texel = 0.02f, size = 0.05f;
  const shaders::SoftLight light = softLight(size, false, near, far, texel);
  Image depth(kMapSize, kMapSize, 1);
  for (int y = 0; y < kMapSize; ++y) {
    for (int x = 0; x < kMapSize; ++x) depth.at(x, y) = x < 120 ? 0.3f : 0.9f;
  }
  LookupPixel pixel;
  pixel.uv = {118.5f / float(kMapSize), 64.5f / float(kMapSize)};
  pixel.receiverDepth = 0.5f;
  const LookupSample esm =
      CpuShadowLookup(depth, softConfig(Technique::Esm, FilterMode::Trilinear, light))
          .lookup(pixel);
  ASSERT_EQ(esm.diagnostic, 1.0f) << "the pixel must fail classification";
  // PCSS with the fallback's test (receiver plane, the reference's tie, no slope bias).
  LookupConfig pcss = softConfig(Technique::Pcf, FilterMode::Trilinear, light);
  pcss.params.pcf.receiverPlane = 1;
  pcss.params.pcf.bias.constantBias = shaders::kReferenceTie;
  pcss.params.pcf.bias.slopeScaledBias = 0.0f;
  const float expected = CpuShadowLookup(depth, pcss).lookup(pixel).visibility;
  EXPECT_GT(expected, 0.2f);  // 3.5 of the box's 10 texels lie past the edge
  EXPECT_LT(expected, 0.5f);
  EXPECT_EQ(esm.visibility, expected);  // the same shared function on the same taps
}

TEST(SoftShadows, EveryTechniquesSoftVariantIsAVisibilityAndLitWhereNothingOccludes) {
  const shaders::SoftLight light = softLight(0.05f, false, 10.0f, 30.0f, 0.02f);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Image noise(64, 64, 1);
  for (float& z : noise.data()) z = unit(random);
  // A blocker at depth 0.1 in x < 16 and the receiver plane at 0.4 beyond it.
  Image blocked(64, 64, 1);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) blocked.at(x, y) = x < 16 ? 0.1f : 0.4f;
  }
  for (Technique t : allTechniques()) {
    for (FilterMode f : {FilterMode::Trilinear, FilterMode::Anisotropic}) {
      // Random depths, receivers from the near plane to beyond the far one, footprints from
      // none to the whole map: finite and within [0, 1].
      const CpuShadowLookup onNoise(noise, softConfig(t, f, light));
      for (int i = 0; i < 400; ++i) {
        LookupPixel p;
        p.uv = {unit(random), unit(random)};
        p.receiverDepth = 1.2f * unit(random) - 0.1f;
        const float footprint = std::pow(10.0f, -6.0f + 6.0f * unit(random));
        p.uvDx = {footprint, 0.0f};
        p.uvDy = {0.0f, footprint * unit(random)};
        p.depthPerTexel = {0.01f * (unit(random) - 0.5f), 0.01f * (unit(random) - 0.5f)};
        const float v = onNoise.lookup(p).visibility;
        ASSERT_TRUE(std::isfinite(v)) << techniqueId(t);
        ASSERT_GE(v, 0.0f) << techniqueId(t);
        ASSERT_LE(v, 1.0f) << techniqueId(t);
      }
      // In front of every texel of the map: nothing between the receiver and the light.
      LookupPixel front;
      front.uv = {0.37f, 0.61f};
      front.receiverDepth = 0.0f;
      EXPECT_EQ(onNoise.lookup(front).visibility, 1.0f)
          << techniqueId(t) << " " << filterModeName(f) << " in front of everything";
      // Beyond the blocker's reach: the search region (s (z_r - near) / texel = 10 texels wide
      // for z_r = 18) around x = 40 holds no texel in front of the receiver.
      const CpuShadowLookup onEdge(blocked, softConfig(t, f, light));
      LookupPixel p;
      p.uv = {40.5f / 64.0f, 0.5f};
      p.receiverDepth = 0.4f;
      EXPECT_EQ(onEdge.lookup(p).visibility, 1.0f) << techniqueId(t) << " " << filterModeName(f);
    }
  }
}

TEST(AreaLight, StratifiedDiskSamplesCoverTheDiskEvenly) {
  const std::vector<glm::vec2> points = stratifiedDiskSamples(256);
  ASSERT_EQ(points.size(), 256u);
  glm::vec2 mean(0.0f);
  int inner = 0;
  for (glm::vec2 p : points) {
    EXPECT_LE(glm::length(p), 1.0f + 1e-6f);
    mean += p / 256.0f;
    inner += glm::length(p) < std::sqrt(0.5f);  // the inner half of the disk's area
  }
  // The concentric map keeps area: each grid cell is 1/256 of the disk, the cells' centres are
  // symmetric about both axes, and the circle of half the area cuts through one ring of cells
  // (16 cells per ring at most on each side of the boundary).
  EXPECT_NEAR(mean.x, 0.0f, 1e-6f);
  EXPECT_NEAR(mean.y, 0.0f, 1e-6f);
  EXPECT_NEAR(inner, 128, 16);
}

TEST(AreaLight, StratifiedSphereSamplesCoverTheSphereEvenly) {
  const std::vector<glm::vec3> points = stratifiedSphereSamples(256);
  ASSERT_EQ(points.size(), 256u);
  glm::vec3 mean(0.0f);
  int cap = 0;
  for (glm::vec3 p : points) {
    EXPECT_NEAR(glm::length(p), 1.0f, 1e-6f);
    mean += p / 256.0f;
    cap += p.z > 0.5f;  // the cap z > 1/2 holds a quarter of the sphere's area
  }
  // Archimedes' map keeps area: z is uniform in u, so the cap's rows of the 16 x 16 grid are
  // exactly the first 4 (64 points), and the rows' centres are symmetric about z = 0 and each
  // ring's about the axis (fp32 sums: 1e-6).
  EXPECT_NEAR(mean.x, 0.0f, 1e-6f);
  EXPECT_NEAR(mean.y, 0.0f, 1e-6f);
  EXPECT_NEAR(mean.z, 0.0f, 1e-6f);
  EXPECT_EQ(cap, 64);
}

TEST(AreaLight, SphereSampleWeightsSumToTheSolidAngleOfTheSilhouette) {
  Light bulb;
  bulb.kind = LightKind::Point;
  bulb.position = glm::vec3(1.0f, 2.0f, -1.0f);
  bulb.size = 1.0f;  // radius 1/2
  for (const float distance : {0.75f, 1.5f, 5.0f}) {
    const glm::vec3 receiver = bulb.position + distance * glm::normalize(glm::vec3(1, -2, 0.5f));
    // Each sample stands for 4 pi r^2 / N of the surface; its weight times that area is the
    // solid angle of its patch from the receiver, 0 for the far side.
    const std::vector<glm::vec3> points = stratifiedSphereSamples(1024);
    double sum = 0.0;
    int seen = 0;
    for (glm::vec3 p : points) {
      const float w = sphereLightSampleWeight(bulb, p, receiver);
      EXPECT_GE(w, 0.0f);
      sum += double(w);
      seen += w > 0.0f;
    }
    const double r = 0.5;
    const double solidAngle = sum * 4.0 * glm::pi<double>() * r * r / double(points.size());
    const double exact =
        2.0 * glm::pi<double>() * (1.0 - std::sqrt(1.0 - r * r / (distance * distance)));
    // The visible cap is 1 - r / D of the sphere (its rim where the tangent cone touches): about
    // that share of the samples sees the receiver. The stratified sum's error: the cells cut by
    // the cap's rim (about 2 side of them), each off by at most its own share, 2 / 32 of the
    // whole at most, and far less as the weights vanish at the rim: 2% asked.
    EXPECT_NEAR(double(seen) / double(points.size()), 0.5 * (1.0 - r / distance), 0.03) << distance;
    EXPECT_NEAR(solidAngle / exact, 1.0, 0.02) << distance;
  }
}

TEST(AreaLight, SamplesCountsOutsideTheStratifiedSquaresAreRefused) {
  EXPECT_THROW(stratifiedDiskSamples(63), Error);
  EXPECT_THROW(stratifiedDiskSamples(65), Error);
  EXPECT_THROW(stratifiedDiskSamples(2048), Error);
  EXPECT_NO_THROW(checkAreaLightSamples(64));
  EXPECT_NO_THROW(checkAreaLightSamples(1024));
}

TEST(AreaLight, DirectionalSamplesFillTheConeOfTheLightsAngularSize) {
  Light sun;
  sun.kind = LightKind::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.size = 0.2f;  // tan of the angular diameter: the rim is atan(0.1) off the axis
  float widest = 0.0f;
  for (glm::vec2 p : stratifiedDiskSamples(64)) {
    const Light s = areaLightSample(sun, p);
    EXPECT_EQ(s.size, 0.0f);
    const float tangent = std::tan(std::acos(std::min(1.0f, glm::dot(s.direction, sun.direction))));
    EXPECT_NEAR(tangent, 0.1f * glm::length(p), 1e-4f);
    widest = std::max(widest, tangent);
  }
  EXPECT_GT(widest, 0.085f);  // the outer ring of an 8 x 8 grid lies at 7/8 of the radius
}

TEST(AreaLight, LightSizesOutOfRangeAreRefusedWithTheRange) {
  Light spot;
  spot.kind = LightKind::Spot;
  spot.size = 10.5f;
  EXPECT_THROW(checkLightSize(spot), Error);
  spot.size = std::nanf("");
  EXPECT_THROW(checkLightSize(spot), Error);
  Light sun;
  sun.size = 0.6f;
  try {
    checkLightSize(sun);
    FAIL() << "a directional light of size 0.6 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("[0, 0.5"), std::string::npos) << e.what();
  }
  sun.size = -0.1f;
  EXPECT_THROW(checkLightSize(sun), Error);
}

TEST(AreaLight, LightSizeOverridesAreCheckedAgainstTheFinalLightsKind) {
  Scene scene = makeBuiltinScene("penumbrae");  // directional
  SceneOverrides o;
  o.lightSize = 0.05f;
  applyOverrides(scene, o);
  EXPECT_EQ(scene.light.size, 0.05f);
  o.lightSize = 5.0f;  // a spot light's range, not a directional light's
  EXPECT_THROW(applyOverrides(scene, o), Error);
  o.lightPosition = glm::vec3(0.0f, 8.0f, 0.0f);  // the same size on a spot light
  applyOverrides(scene, o);
  EXPECT_EQ(scene.light.kind, LightKind::Spot);
  EXPECT_EQ(scene.light.size, 5.0f);
}

}  // namespace
}  // namespace penumbra
