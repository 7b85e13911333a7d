// Moment shadow maps (Peters & Klein 2015, docs/papers.md): the quantisation
// matrices, the Hamburger reconstruction on hand-computed cases, bounds and degenerate moments.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "penumbra/depth_distribution.h"
#include "penumbra/error.h"
#include "penumbra/params.h"
#include "region_helpers.h"
#include "penumbra/shared/msm.h"

namespace penumbra {
namespace {

using testing::float32Params;

TEST(Msm, QuantisationMatricesAreInverses) {
  const glm::mat4 product = shaders::msmDequantizationMatrix() * shaders::msmQuantizationMatrix();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(product[i][j], i == j ? 1.0f : 0.0f, 2e-5f);
  }
}

TEST(Msm, QuantisedMomentsStayInTheUnitRange) {
  shaders::MsmParams p = shaders::msmDefaultParams();
  for (int i = 0; i <= 1000; ++i) {
    const glm::vec4 q = shaders::msmEncode(float(i) / 1000.0f, p);
    for (int c = 0; c < 4; ++c) {
      EXPECT_GE(q[c], -1e-6f);
      EXPECT_LE(q[c], 1.0f + 1e-6f);
    }
    const glm::vec4 b = shaders::msmDecode(q, p);
    EXPECT_NEAR(b.x, float(i) / 1000.0f, 1e-5f);
  }
}

// Two atoms: a with weight w and b with 1 - w. By hand (notes step 4), the roots are a and b,
// so G = w between them (z2 < zf <= z3 case) and 1 beyond b: exactly what PCF returns.
TEST(Msm, TwoAtomDistributionMatchesTheHandComputedIntensity) {
  TechniqueParams params = float32Params();
  const std::vector<DepthSample> region{{0.2f, 0.3f}, {0.6f, 0.7f}};
  EXPECT_NEAR(evaluateOnRegion(Technique::Msm, params, region, 0.4f), 0.7f, 2e-3f);
  EXPECT_NEAR(evaluateOnRegion(Technique::Msm, params, region, 0.8f), 0.0f, 2e-3f);
  EXPECT_NEAR(evaluateOnRegion(Technique::Msm, params, region, 0.1f), 1.0f, 1e-6f);
}

TEST(Msm, MomentBiasFollowsTheStorageUnlessSetExplicitly) {
  // The notes' alpha: 3e-5 for 16-bit storage, 3e-6 for 32-bit; a value the user gives is kept,
  // whatever the order of the assignments.
  const TechniqueParams defaults = defaultTechniqueParams();
  EXPECT_EQ(formatParam(Technique::Msm, defaults, "momentBias"), "auto");
  EXPECT_EQ(shaders::msmMomentBias(defaults.msm), 3e-5f);
  TechniqueParams p = defaults;
  setParam(Technique::Msm, p, "storage", "float32");
  EXPECT_EQ(shaders::msmMomentBias(p.msm), 3e-6f);
  EXPECT_NO_THROW(validateParams(Technique::Msm, p));
  for (bool biasFirst : {true, false}) {
    TechniqueParams q = defaults;
    if (biasFirst) setParam(Technique::Msm, q, "momentBias", "1e-4");
    setParam(Technique::Msm, q, "storage", "float32");
    if (!biasFirst) setParam(Technique::Msm, q, "momentBias", "1e-4");
    EXPECT_EQ(shaders::msmMomentBias(q.msm), 1e-4f) << biasFirst;
    setParam(Technique::Msm, q, "momentBias", "auto");
    EXPECT_EQ(shaders::msmMomentBias(q.msm), 3e-6f);
  }
  EXPECT_THROW(setParam(Technique::Msm, p, "momentBias", "-1"),
               Error);  // the sentinel is not input

  // The reconstruction uses it: float32 storage by default reconstructs as with 3e-6, not 3e-5.
  TechniqueParams small = p, large = p;
  small.msm.momentBias = 3e-6f;
  large.msm.momentBias = 3e-5f;
  const std::vector<DepthSample> region{{0.2f, 0.3f}, {0.6f, 0.7f}};
  float largestDifference = 0.0f;
  for (float receiver : {0.3f, 0.5f, 0.61f, 0.7f}) {
    const float v = evaluateOnRegion(Technique::Msm, p, region, receiver);
    EXPECT_EQ(v, evaluateOnRegion(Technique::Msm, small, region, receiver)) << receiver;
    largestDifference = std::max(
        largestDifference, std::abs(v - evaluateOnRegion(Technique::Msm, large, region, receiver)));
  }
  EXPECT_GT(largestDifference, 1e-4f);
}

using Moments = std::array<long double, 4>;

// Shadow intensity from power moments, the notes' steps 1-4 in long double, independently of
// shared/msm.h: bias toward (1/2, 1/2, 1/2, 1/2), the Hankel system by Cramer's rule, the roots of
// c3 z^2 + c2 z + c1 in cancellation-free form, the three cases.
long double independentMsmIntensity(Moments b, long double zf, long double alpha) {
  for (long double& m : b) m = (1.0L - alpha) * m + alpha * 0.5L;
  auto det3 = [](long double a, long double b_, long double c, long double d, long double e,
                 long double f, long double g, long double h, long double i) {
    return a * (e * i - f * h) - b_ * (d * i - f * g) + c * (d * h - e * g);
  };
  const long double r1 = zf, r2 = zf * zf;
  const long double det = det3(1, b[0], b[1], b[0], b[1], b[2], b[1], b[2], b[3]);
  const long double c1 = det3(1, b[0], b[1], r1, b[1], b[2], r2, b[2], b[3]) / det;
  const long double c2 = det3(1, 1, b[1], b[0], r1, b[2], b[1], r2, b[3]) / det;
  const long double c3 = det3(1, b[0], 1, b[0], b[1], r1, b[1], b[2], r2) / det;
  const long double root = std::sqrt(std::max(c2 * c2 - 4.0L * c1 * c3, 0.0L));
  const long double q = -0.5L * (c2 + (c2 < 0.0L ? -root : root));
  const long double z2 = std::min(q / c3, c1 / q), z3 = std::max(q / c3, c1 / q);
  if (zf <= z2) return 0.0L;
  if (zf <= z3) {
    return std::clamp((zf * z3 - b[0] * (zf + z3) + b[1]) / ((z3 - z2) * (zf - z2)), 0.0L, 1.0L);
  }
  return std::clamp(1.0L - (z2 * z3 - b[0] * (z2 + z3) + b[1]) / ((zf - z2) * (zf - z3)), 0.0L,
                    1.0L);
}

// The 16-bit path (optimised quantisation, notes "Storage") can only move the decoded moments by
// what unorm16 rounding of q does: at most half a step (1/65535) when each depth is encoded and
// half a step when the filtered value is stored again, so |dq_i| <= 1/65535, and the decoded
// moments are b + D^T dq. Its visibility must therefore lie in the range the reconstruction
// takes over that parallelepiped, brute-forced here over the lattice dq_i in {-1, 0, 1} steps
// (the range is first-order in dq, so its extremes sit on the lattice's corners), widened by
// 2e-3 for fp32 evaluation: MSM amplifies rounding by about 1/alpha = 3e4 (docs/techniques.md),
// and 3e4 x 6e-8 = 2e-3. The ranges are wide where the Hankel system is ill-conditioned, but
// narrow over the cluster near the far plane below, where storing the raw powers in unorm16 (the
// transform skipped) leaves them at receivers from 0.75 to 0.95: that break fails here.
TEST(Msm, SixteenBitResultIsTheReconstructionOfMomentsWithinOneQuantisationStep) {
  TechniqueParams p16 = float32Params();
  p16.msm.storage = shaders::kStorageUnorm16;
  p16.msm.momentBias = 3e-5f;
  p16.msm.depthBias = 0.0f;
  const glm::mat4 dequantize = shaders::msmDequantizationMatrix();  // dequantize[i][j] = D[i][j]
  const std::vector<std::vector<DepthSample>> regions{{{0.2f, 0.3f}, {0.6f, 0.7f}},
                                                      {{0.7f, 0.3f}, {0.75f, 0.3f}, {0.9f, 0.4f}},
                                                      {{0.85f, 0.5f}, {0.95f, 0.5f}}};
  for (const std::vector<DepthSample>& region : regions) {
    Moments exact{};
    long double weight = 0.0L;
    for (const DepthSample& s : region) weight += s.weight;
    for (const DepthSample& s : region) {
      for (int j = 0; j < 4; ++j)
        exact[j] += s.weight / weight * std::pow(static_cast<long double>(s.depth), j + 1);
    }
    for (int i = 1; i < 20; ++i) {
      const float receiver = float(i) / 20.0f;
      long double lowest = 1.0L, highest = 0.0L;
      for (int corner = 0; corner < 81; ++corner) {
        Moments b = exact;
        for (int k = 0, code = corner; k < 4; ++k, code /= 3) {
          const long double step = (code % 3 - 1) / 65535.0L;
          for (int j = 0; j < 4; ++j) b[j] += step * dequantize[k][j];
        }
        const long double v = 1.0L - independentMsmIntensity(b, receiver, 3e-5L);
        lowest = std::min(lowest, v);
        highest = std::max(highest, v);
      }
      const float v16 = evaluateOnRegion(Technique::Msm, p16, region, receiver);
      EXPECT_GE(v16, lowest - 2e-3L) << "receiver " << receiver << " over " << region[0].depth;
      EXPECT_LE(v16, highest + 2e-3L) << "receiver " << receiver << " over " << region[0].depth;
    }
  }
}

TEST(Msm, DegenerateMomentsGiveBoundedFiniteResults) {
  for (float bias : {3e-6f, 3e-5f}) {
    for (glm::vec4 b : {glm::vec4(0.0f), glm::vec4(1.0f), shaders::msmPowers(0.5f)}) {
      for (float zf : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        const float g = shaders::msmShadowIntensity(b, zf, bias);
        EXPECT_TRUE(std::isfinite(g));
        EXPECT_GE(g, 0.0f);
        EXPECT_LE(g, 1.0f);
      }
    }
  }
  // A single depth: in front of it lit, far behind it shadowed.
  EXPECT_NEAR(shaders::msmShadowIntensity(shaders::msmPowers(0.5f), 0.3f, 3e-6f), 0.0f, 1e-3f);
  EXPECT_NEAR(shaders::msmShadowIntensity(shaders::msmPowers(0.5f), 0.8f, 3e-6f), 1.0f, 1e-2f);
}

}  // namespace
}  // namespace penumbra
