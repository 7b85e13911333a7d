// CSM (CSM paper §3): the Fourier step reconstruction improves with M, attenuation trades
// ringing for steepness, the offset lights lit surfaces, the basis fits 8-bit storage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "penumbra/depth_distribution.h"
#include "penumbra/error.h"
#include "penumbra/params.h"
#include "region_helpers.h"
#include "penumbra/shared/csm.h"

namespace penumbra {
namespace {

using testing::float32Params;

// The unclamped series for one occluder at z and a receiver at d.
float series(float occluder, float receiver, const shaders::CsmParams& p) {
  glm::vec4 basis[8];
  for (int t = 0; t < 8; ++t) basis[t] = shaders::csmEncodeTexture(occluder, t, p);
  return shaders::csmSeries(basis, receiver, p);
}

// Mean |f - H(z - d)| over z - d in [-0.9, 0.9], skipping the jump's immediate neighbourhood.
// Depths are scaled by kappa inside the expansion; z - d here is in those scaled units.
float meanStepError(const shaders::CsmParams& p) {
  double error = 0.0;
  int count = 0;
  for (int i = -900; i <= 900; ++i) {
    const float t = float(i) / 1000.0f;
    if (std::abs(t) < 0.02f) continue;
    const float kappa = shaders::csmDepthScale(p);
    const float z = (0.5f + t / 2.0f) / kappa,
                d = (0.5f - t / 2.0f) / kappa;  // kappa z - kappa d = t
    error += std::abs(series(z, d, p) - (t > 0.0f ? 1.0f : 0.0f));
    ++count;
  }
  return float(error / count);
}

TEST(Csm, StepReconstructionErrorShrinksFromFourToEightToSixteenTerms) {
  const float e4 = meanStepError(shaders::csmPlainSeriesParams(4));
  const float e8 = meanStepError(shaders::csmPlainSeriesParams(8));
  const float e16 = meanStepError(shaders::csmPlainSeriesParams(16));
  EXPECT_GT(e4, e8);
  EXPECT_GT(e8, e16);
  EXPECT_LT(e16, 0.03f);
}

TEST(Csm, SeriesIsTheFourierExpansionOfTheStep) {
  // CSM eq. 11 evaluated directly for one occluder: 1/2 + sum 2/c_k sin(c_k (z - d)).
  const shaders::CsmParams p = shaders::csmPlainSeriesParams(5);
  const float z = 0.62f, d = 0.41f;
  const double kappa = 1.0 - 1.0 / 10.0;  // 1 - (1 + offset 0) / (2M)
  EXPECT_FLOAT_EQ(shaders::csmDepthScale(p), float(kappa));
  double expected = 0.5;
  for (int k = 1; k <= 5; ++k) {
    const double c = M_PI * (2 * k - 1);
    expected += 2.0 / c * std::sin(c * kappa * (z - d));
  }
  EXPECT_NEAR(series(z, d, p), expected, 2e-5);
}

TEST(Csm, AttenuationReducesOvershoot) {
  auto overshoot = [](float alpha) {
    shaders::CsmParams p = shaders::csmPlainSeriesParams(8);
    p.attenuation = alpha;
    float peak = 0.0f;
    for (int i = 1; i < 500; ++i) peak = std::max(peak, series(0.5f, 0.5f - float(i) / 1000.0f, p));
    return peak - 1.0f;
  };
  EXPECT_GT(overshoot(0.0f), 0.05f);  // Gibbs: about 9% of the jump
  EXPECT_LT(overshoot(1.0f), overshoot(0.0f));
  EXPECT_LT(overshoot(4.0f), overshoot(1.0f));
}

TEST(Csm, OffsetMakesALitReceiverLit) {
  for (int terms : {4, 8, 16}) {
    shaders::CsmParams p = shaders::csmPlainSeriesParams(terms);
    EXPECT_NEAR(series(0.4f, 0.4f, p), 0.5f, 1e-5f) << "unshifted series is half lit at z = d";
    p.offsetScale = 1.0f;
    EXPECT_GT(series(0.4f, 0.4f, p), 0.99f) << "M = " << terms;
    glm::vec4 basis[8];
    for (int t = 0; t < 8; ++t) basis[t] = shaders::csmEncodeTexture(0.4f, t, p);
    EXPECT_EQ(shaders::csmVisibility(basis, 0.4f, p), 1.0f);
  }
}

TEST(Csm, NoDepthPairWrapsAroundThePeriod) {
  // A receiver at the light with an occluder at the far plane is lit; the reverse is shadowed.
  for (int terms : {4, 8, 16}) {
    shaders::CsmParams p = shaders::csmDefaultParams();
    p.termCount = terms;
    EXPECT_GT(series(1.0f, 0.0f, p), 0.95f) << "M = " << terms;
    EXPECT_LT(series(0.0f, 1.0f, p), 0.05f) << "M = " << terms;
  }
}

TEST(Csm, NoAcceptedTermCountAndOffsetWrapsALitReceiver) {
  // Sweeps every (M, offset) the registry accepts, through encode and reconstruct. A receiver in
  // front of (or at) its occluder sits on the lit half of the truncated step, t in [0, 1): the
  // series is >= 1/2 there (its partial sums are positive on (0, 1), and attenuation only weights
  // them down monotonically); a wrap past t = 1 reads below 1/2. Float32 storage keeps storage
  // rounding out (EightBitStorageStaysCloseToFloat covers it); 1e-4 is fp32 rounding of at most
  // 16 terms at t = 0 (offset 0, z = d), where the series is exactly 1/2.
  // Receivers at least one ringing width 1/(2M) in front read >= 0.73 for alpha <= 1: the
  // lowest plateau is M = 1, alpha = 1: 1/2 + (2/pi) e^-1 = 0.734.
  int accepted = 0;
  for (int terms = 1; terms <= shaders::kCsmMaxTerms; ++terms) {
    for (int quarter = 0; quarter <= 16; ++quarter) {
      const float offset = float(quarter) / 4.0f;
      TechniqueParams p = float32Params();
      setParam(Technique::Csm, p, "M", std::to_string(terms));
      setParam(Technique::Csm, p, "offset", std::to_string(offset));
      try {
        validateParams(Technique::Csm, p);
      } catch (const Error& e) {
        EXPECT_GT(offset, float(terms - 1)) << "M = " << terms << " offset " << offset;
        EXPECT_NE(std::string(e.what()).find("must not exceed M - 1"), std::string::npos);
        continue;
      }
      ++accepted;
      const float kappa = shaders::csmDepthScale(p.csm);
      for (float alpha : {0.0f, 1.0f, 20.0f}) {
        p.csm.attenuation = alpha;
        float lowest = 1.0f, lowestClear = 1.0f;
        for (int i = 0; i <= 64; ++i) {
          const float occluder = float(i) / 64.0f;
          float channels[2 * shaders::kCsmMaxTerms];
          encodeDepth(Technique::Csm, p, occluder, channels);
          for (int j = 0; j <= i; ++j) {
            const float receiver = float(j) / 64.0f;
            const float v = reconstructVisibility(Technique::Csm, p,
                                                  std::span(channels, size_t(2 * terms)), receiver);
            lowest = std::min(lowest, v);
            if (kappa * (occluder - receiver) >= 0.5f / float(terms)) {
              lowestClear = std::min(lowestClear, v);
            }
          }
        }
        const std::string where = "M = " + std::to_string(terms) +
                                  " offset = " + std::to_string(offset) +
                                  " alpha = " + std::to_string(alpha);
        EXPECT_GE(lowest, 0.5f - 1e-4f) << where;
        if (alpha <= 1.0f) {
          EXPECT_GE(lowestClear, 0.73f) << where;
        }
      }
    }
  }
  EXPECT_EQ(accepted, 1 + 5 + 9 + 13 + 12 * 17);  // M = 1..4 take offsets up to M - 1 only
}

// Receiver-depth distance over which one occluder's visibility falls from 0.9 to 0.1, found by a
// sweep of 1e-5 steps from z - 0.2 (the first receiver below 0.9, then the first below 0.1).
float transitionWidth(float occluder, const shaders::CsmParams& p) {
  glm::vec4 basis[8];
  for (int t = 0; t < 8; ++t) basis[t] = shaders::csmEncodeTexture(occluder, t, p);
  float below90 = -1.0f;
  for (int i = 0; i <= 40000; ++i) {
    const float d = occluder - 0.2f + float(i) * 1e-5f;
    const float v = shaders::csmVisibility(basis, d, p);
    if (below90 < 0.0f && v < 0.9f) below90 = d;
    if (v < 0.1f) return d - below90;
  }
  return -1.0f;
}

// CSM §3.2.2, Fig. 3(d): scaling the expansion by 2 makes the transition steeper and lights a
// receiver at the occluder's depth (the unshifted series reads 1/2 there). Were the series a
// linear ramp through the step, 0.9..0.1 of the scaled result would be 0.45..0.05 of the series,
// half the span of 0.9..0.1: a width factor of exactly 1/2. The truncated series flattens toward
// its foot (0.05), so the factor is a little above 1/2: 0.56 for M = 8 with the default
// attenuation, from eq. 11 evaluated in double. Ignoring the scale gives 1; scaling about 1/2
// (2f - 1/2, steeper without lighting) gives less than 1/2.
TEST(Csm, ScalingByTwoHalvesTheTransitionAndLightsTheOccludersOwnDepth) {
  shaders::CsmParams p = shaders::csmPlainSeriesParams(8);
  p.attenuation = shaders::csmDefaultParams().attenuation;
  const float unscaled = transitionWidth(0.5f, p);
  p.scale = 2.0f;
  const float scaled = transitionWidth(0.5f, p);
  ASSERT_GT(unscaled, 0.0f);
  ASSERT_GT(scaled, 0.0f);
  EXPECT_GT(scaled / unscaled, 0.5f);
  EXPECT_LT(scaled / unscaled, 0.6f);
  glm::vec4 basis[8];
  for (int t = 0; t < 8; ++t) basis[t] = shaders::csmEncodeTexture(0.4f, t, p);
  // At d = z the terms cancel but for the basis's map to [0,1] and back, which rounds each value
  // by up to 6e-8; the series weighs them by sum 2/c_k (1.3 for M = 8) and the scale doubles it.
  EXPECT_NEAR(shaders::csmVisibility(basis, 0.4f, p), 1.0f, 3.2e-7f);
}

// The encode walks the textures by Chebyshev's recurrence (csmBasisWalk). Against sin and cos
// of c_k z in double, every term of every texture stays within 5e-6 of the [0,1]-mapped basis
// (1e-5 before the map): evaluating each term directly in float is off by up to 3.6e-6 after the
// map at k = 16, where the argument 31 pi z (up to 91) rounds by half an ulp, and the walk
// measured 4.3e-6 over 200001 depths (this grid: 3.6e-6). The recurrence multiplies its start's
// and step's roundings by up to its 7 steps, the step's by their square where sin 4 pi z = 0:
// with cos(4 pi z) as cos^2 2 pi z - sin^2 2 pi z everywhere instead of the form chosen per
// depth (csmBasisWalk) it measured 1.9e-5. A wrong recurrence or start is off by O(1).
TEST(Csm, BasisRecurrenceStaysWithinItsRoundingOfTheDirectBasis) {
  const shaders::CsmParams p = shaders::csmDefaultParams();
  float worst = 0.0f;
  for (int i = 0; i <= 4000; ++i) {
    const float depth = float(i) / 4000.0f;
    const double z = double(shaders::csmDepthScale(p)) * double(depth);
    for (int t = 0; t < shaders::csmTextureCount(p); ++t) {
      const glm::vec4 b = shaders::csmEncodeTexture(depth, t, p);
      for (int term = 0; term < 2; ++term) {
        const double c = M_PI * double(2 * (2 * t + term + 1) - 1);
        worst = std::max(worst, float(std::abs(b[2 * term] - (0.5 + 0.5 * std::sin(c * z)))));
        worst = std::max(worst, float(std::abs(b[2 * term + 1] - (0.5 + 0.5 * std::cos(c * z)))));
      }
    }
  }
  EXPECT_LT(worst, 5.0e-6f);
  EXPECT_GT(worst, 0.0f);  // float arithmetic: exactness would mean the test reads nothing
}

// (The basis's range needs no test of its own: within 5e-6 of the exact basis, above, it is within
// rounding of [0, 1], which unorm storage clamps as it converts:
// StorageFormat.UnormRoundsToTheNearestCodeAwayFromTies.)
TEST(Csm, PacksTwoTermsPerTexture) {
  shaders::CsmParams p = shaders::csmDefaultParams();
  p.termCount = 16;
  EXPECT_EQ(shaders::csmTextureCount(p), 8);  // 2M channels = M/2 RGBA textures
  p.termCount = 4;
  EXPECT_EQ(shaders::csmTextureCount(p), 2);
}

// The CSM reconstruction of a filtered region computed here in double from eq. 11-14, independently
// of shared/csm.h: depths scaled by kappa, the receiver offset by offset/(2M), terms attenuated
// by exp(-alpha (k/M)^2), the filtered sum of sin(c_k (kappa z - d')), then scaled and clamped.
double independentCsmVisibility(const std::vector<DepthSample>& region, float receiver,
                                const shaders::CsmParams& p) {
  const int m = p.termCount;
  const double kappa = std::max(0.5, 1.0 - (1.0 + p.offsetScale) / (2.0 * m));
  const double d = kappa * receiver - p.offsetScale / (2.0 * m);
  double weight = 0.0;
  for (const DepthSample& s : region) weight += s.weight;
  double f = 0.5;
  for (int k = 1; k <= m; ++k) {
    const double c = M_PI * (2 * k - 1);
    const double attenuation = std::exp(-p.attenuation * double(k * k) / double(m * m));
    double filtered = 0.0;
    for (const DepthSample& s : region) filtered += s.weight * std::sin(c * (kappa * s.depth - d));
    f += attenuation * 2.0 / c * filtered / weight;
  }
  return std::clamp(p.scale * f, 0.0, 1.0);
}

// The most unorm8 storage can move the reconstruction. Each basis value is stored as 1/2 + B/2 and
// rounded to 1/255 steps twice (encoded, then filtered; the filter is a convex combination, so
// the first rounding stays within 1/2 step): |error| <= 1/255 stored, 2/255 in B, for sin and
// cos alike. Term k adds a_k (2/c_k) (sinZ cos(c_k d) - cosZ sin(c_k d)), which moves by at most
// a_k (2/c_k) sqrt(2) 2/255 (Cauchy-Schwarz); the scale multiplies and the clamp cannot enlarge.
double unorm8ReconstructionBound(const shaders::CsmParams& p) {
  double sum = 0.0;
  for (int k = 1; k <= p.termCount; ++k) {
    const double c = M_PI * (2 * k - 1);
    sum += std::exp(-p.attenuation * double(k * k) / double(p.termCount * p.termCount)) * 2.0 / c;
  }
  return p.scale * sum * std::sqrt(2.0) * 2.0 / 255.0;
}

// unorm8 (the paper's storage, §4) over the exact series, within what its rounding can cause:
// about 0.010, 0.012 and 0.015 for M = 4, 8, 16 with the default attenuation. The last term's
// amplitude at M = 4 (0.033) is three times the bound, so dropping a term fails; fp32 evaluation
// (sin and cos of arguments up to 31 pi) adds under 2e-5.
TEST(Csm, EightBitStorageStaysWithinItsRoundingOfTheExactSeries) {
  const std::vector<std::vector<DepthSample>> regions{
      {{0.3f, 0.4f}, {0.6f, 0.6f}}, {{0.1f, 0.25f}, {0.45f, 0.25f}, {0.8f, 0.5f}}, {{0.55f, 1.0f}}};
  for (int terms : {4, 8, 16}) {
    TechniqueParams bytes = float32Params();
    bytes.csm.storage = shaders::kStorageUnorm8;
    bytes.csm.termCount = terms;
    TechniqueParams exact = bytes;
    exact.csm.storage = shaders::kStorageFloat32;
    const double bound = unorm8ReconstructionBound(bytes.csm) + 2e-5;
    double largestStorageError = 0.0;
    for (const std::vector<DepthSample>& region : regions) {
      for (int i = 0; i <= 100; ++i) {
        const float receiver = float(i) / 100.0f;
        const double expected = independentCsmVisibility(region, receiver, bytes.csm);
        const float stored = evaluateOnRegion(Technique::Csm, bytes, region, receiver);
        EXPECT_NEAR(stored, expected, bound) << "M = " << terms << ", receiver " << receiver;
        EXPECT_NEAR(evaluateOnRegion(Technique::Csm, exact, region, receiver), expected, 2e-5)
            << "float32, M = " << terms << ", receiver " << receiver;
        largestStorageError = std::max(largestStorageError, std::abs(stored - expected));
      }
    }
    // The reference must see the 8-bit rounding the GPU textures hold (docs/architecture.md):
    // over 300 lookups some error beyond a tenth of a step shows up.
    EXPECT_GT(largestStorageError, 0.1 / 255.0) << "M = " << terms;
  }
}

}  // namespace
}  // namespace penumbra
