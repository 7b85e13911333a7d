// Invariants every technique must keep, swept over all of them at once: visibility in [0,1],
// non-increasing in receiver depth, lit when nothing occludes, finite at extreme inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "penumbra/depth_distribution.h"
#include "penumbra/error.h"
#include "penumbra/params.h"
#include "penumbra/storage_format.h"
#include "region_helpers.h"
#include "shared/layers.h"
#include "shared/technique_dispatch.h"

namespace penumbra {
namespace {

using testing::visibility;

class TechniqueInvariants : public ::testing::TestWithParam<Technique> {
 protected:
  TechniqueParams params = defaultTechniqueParams();
};

// Random regions: 1-4 occluders with random depths and shares.
std::vector<DepthSample> randomOccluders(std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<DepthSample> occluders;
  const int count = 1 + int(rng() % 4);
  float remaining = 1.0f;
  for (int i = 0; i < count; ++i) {
    const float w = remaining * (0.1f + 0.8f * unit(rng));
    occluders.push_back({unit(rng), w});
    remaining -= w;
  }
  return occluders;
}

TEST_P(TechniqueInvariants, VisibilityStaysInUnitRange) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 400; ++i) {
    const auto occluders = randomOccluders(rng);
    const float v = visibility(GetParam(), params, occluders, unit(rng));
    ASSERT_TRUE(std::isfinite(v));
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
}

// How far visibility may rise with receiver depth: float rounding, except CSM, whose truncated
// Fourier series rings (CSM §3.2.1; the default attenuation keeps it to this measured bound).
float allowedRise(Technique t) {
  return t == Technique::Csm ? 0.02f : 1e-5f;
}

// Receiver depths whose visibilities a technique promises to order. LVSM reads a different
// layer's moments on each side of a split (thesis §4.1), and a layer's one-tailed bound can be
// looser than the previous layer's, so it is monotone within a layer, away from the transition
// band below each split. CSM's series has period 2 in z - d (CSM eq. 10): receivers within 2/M
// of the light see occluders near depth 1 wrap toward the shadowed half-wave.
bool ordered(Technique t, const TechniqueParams& p, float nearer, float farther) {
  if (t == Technique::Lvsm) {
    const int layer = shaders::selectLayer(nearer, p.lvsm.splits);
    const float top = shaders::layerSplit(p.lvsm.splits, layer + 1);
    return layer == shaders::selectLayer(farther, p.lvsm.splits) &&
           farther < top - p.lvsm.transition;
  }
  if (t == Technique::Csm) return nearer >= 2.0f / float(p.csm.termCount);
  return true;
}

TEST_P(TechniqueInvariants, VisibilityDoesNotIncreaseWithReceiverDepth) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    // A fixed filter region: the curve as the receiver moves behind fixed occluders.
    std::vector<DepthSample> region = randomOccluders(rng);
    float total = 0.0f;
    for (const auto& s : region) total += s.weight;
    for (auto& s : region) s.weight /= total;
    float previous = 1.0f;
    int compared = 0;
    for (int i = 0; i <= 200; ++i) {
      const float receiver = float(i) / 200.0f;
      const float v = evaluateOnRegion(GetParam(), params, region, receiver);
      if (i > 0 && ordered(GetParam(), params, float(i - 1) / 200.0f, receiver)) {
        EXPECT_LE(v, previous + allowedRise(GetParam())) << "receiver " << receiver;
        ++compared;
      }
      previous = v;
    }
    EXPECT_GT(compared, 150);
  }
}

// How far from 1 an unoccluded receiver may come out: CSM's ringing after the offset, and the
// rounding of 16-bit storage (LVSM and MSM by default), which moves moments by up to 2^-17.
float litTolerance(Technique t) {
  if (t == Technique::Csm) return 0.06f;
  if (t == Technique::Lvsm || t == Technique::Msm) return 1e-4f;
  return 0.0f;
}

TEST_P(TechniqueInvariants, IsLitWhenNothingOccludes) {
  for (float receiver : {0.0f, 0.1f, 0.5f, 0.9f}) {
    // The receiver plane alone, and with occluders only behind it.
    EXPECT_NEAR(visibility(GetParam(), params, {}, receiver), 1.0f, litTolerance(GetParam()));
    const float behind = std::min(1.0f, receiver + 0.08f);
    EXPECT_NEAR(visibility(GetParam(), params, {{behind, 0.5f}}, receiver), 1.0f,
                litTolerance(GetParam()))
        << "receiver " << receiver;
  }
}

TEST_P(TechniqueInvariants, StaysFiniteAtExtremeInputs) {
  TechniqueParams extreme = params;
  extreme.evsm.positiveExponent = 42.0f;
  extreme.evsm.negativeExponent = 42.0f;
  extreme.esm.exponent = 88.0f;
  extreme.vsm.minVariance = 0.0f;
  extreme.lvsm.minVariance = 0.0f;
  extreme.evsm.minVariance = 0.0f;
  extreme.msm.momentBias = 0.0f;
  TechniqueParams logEsm = extreme;
  logEsm.esm.filterSpace = shaders::kEsmFilterLog;
  logEsm.esm.exponent = 10000.0f;
  for (const TechniqueParams& p : {params, extreme, logEsm}) {
    for (float occluder : {0.0f, 1.0f}) {
      for (float receiver : {0.0f, 1.0f}) {
        for (float share : {0.0f, 0.5f, 1.0f}) {
          std::vector<DepthSample> occluders;
          if (share > 0.0f) occluders.push_back({occluder, share});
          const float v = visibility(GetParam(), p, occluders, receiver);
          EXPECT_TRUE(std::isfinite(v)) << occluder << " " << receiver << " " << share;
          EXPECT_GE(v, 0.0f);
          EXPECT_LE(v, 1.0f);
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllTechniques, TechniqueInvariants,
                         ::testing::ValuesIn(allTechniques().begin(), allTechniques().end()),
                         [](const ::testing::TestParamInfo<Technique>& test) {
                           return std::string(techniqueId(test.param));
                         });

TEST(TechniqueDispatch, MsmIsItsOwnBranchAndAnUnknownIdReadsLit) {
  // Moments of one depth 0.2 and a receiver far behind it: MSM says shadowed; an id past the last
  // technique must not fall through to MSM (or anything else) but read a defined value, lit.
  float channels[shaders::kMaxChannels] = {};
  TechniqueParams p = defaultTechniqueParams();
  p.msm.storage = shaders::kStorageFloat32;
  for (int c = 0; c < 4; ++c) channels[c] = shaders::msmEncode(0.2f, p.msm)[c];
  EXPECT_LT(shaders::reconstructVisibility(shaders::kTechniqueMsm, channels, 0.8f, p), 0.01f);
  for (int unknown : {shaders::kTechniqueCount, shaders::kTechniqueCount + 7, -1}) {
    EXPECT_EQ(shaders::reconstructVisibility(unknown, channels, 0.8f, p), 1.0f) << unknown;
  }
}

TEST(TechniqueIds, AnIdOutsideTheEnumerationIsRejectedWithTheValidIds) {
  const TechniqueParams p = defaultTechniqueParams();
  float channels[shaders::kMaxChannels] = {};
  for (int id : {10, 42, -1}) {
    const Technique t = static_cast<Technique>(id);
    std::string message;
    try {
      techniqueId(t);
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("technique id " + std::to_string(id) + " is out of range [0, 9]"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("hard, pcf"), std::string::npos) << message;
    EXPECT_THROW(techniqueTitle(t), Error);
    EXPECT_THROW(channelCount(t, p), Error);
    EXPECT_THROW(encodeDepth(t, p, 0.5f, channels), Error);
    EXPECT_THROW(channelReduction(t, p, 0), Error);
    EXPECT_THROW(reconstructVisibility(t, p, channels, 0.5f), Error);
    EXPECT_THROW(filtersAfterTest(t), Error);
    EXPECT_THROW(techniqueStorage(t, p), Error);
    EXPECT_THROW(techniqueParamSpecs(t), Error);
    EXPECT_THROW(validateParams(t, p), Error);
  }
}

}  // namespace
}  // namespace penumbra
