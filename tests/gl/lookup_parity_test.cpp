// The renderer checked pixel by pixel: for every technique x filter mode x storage format on
// small frames of every built-in scene (lantern: a point light's six faces, each pixel against
// its face's twin), the GPU's visibility equals the CPU twin's
// (penumbra/shadow_lookup.h), which runs the same shared lookup over the CPU reference filters,
// on every pixel up to the storage's and the sums' rounding carried through the technique's
// reconstruction; and the GPU's filtered reference equals the CPU twin's reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <utility>

#include "gl_test_context.h"
#include "penumbra/error.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/params.h"
#include "penumbra/shadow_lookup.h"
#include "penumbra/storage_format.h"
#include "rounding_envelope.h"

namespace penumbra {
namespace {

using testing::channelRounding;
using testing::ChannelRounding;
using testing::Envelope;
using testing::kArithmetic;
using testing::kTieRounding;
using testing::roundingEnvelope;

// The CPU twin of the layer pixel (x, y) of a render reads — a point light's face (lantern),
// else the one map — built on first use from that layer's depth map.
class LayerTwins {
 public:
  LayerTwins(const gl::Renderer& renderer, const gl::RenderResult& result, LookupConfig config)
      : renderer_(renderer), result_(result), config_(std::move(config)) {}
  const CpuShadowLookup& at(int x, int y) {
    const int layer = int(result_.cascades.at(x, y, 0));
    std::unique_ptr<CpuShadowLookup>& twin = twins_[layer];
    if (!twin) twin = std::make_unique<CpuShadowLookup>(renderer_.readDepthMap(layer), config_);
    return *twin;
  }

 private:
  const gl::Renderer& renderer_;
  const gl::RenderResult& result_;
  LookupConfig config_;
  std::map<int, std::unique_ptr<CpuShadowLookup>> twins_;
};

struct ParityCase {
  std::string label;
  TechniqueParams params;
  FilterMode filter;
};

class ReferenceParity : public testing::GlTest {};

// |GPU - CPU| over the pixels inside the shadow map, sorted.
struct Differences {
  std::vector<float> values;
  float quantile(double q) const {
    if (values.empty()) return 0.0f;
    return values[std::min(values.size() - 1, size_t(q * double(values.size())))];
  }
  float max() const { return values.empty() ? 0.0f : values.back(); }
};

std::vector<std::string> storageChoices(Technique t) {
  for (const ParamSpec& spec : techniqueParamSpecs(t)) {
    if (spec.name != "storage") continue;
    std::vector<std::string> names;
    for (const ParamChoice& c : spec.choices) names.push_back(std::string(c.name));
    return names;
  }
  return {""};
}

std::vector<ParityCase> casesFor(Technique t) {
  std::vector<ParityCase> cases;
  std::vector<TechniqueParams> variants;
  std::vector<std::string> labels;
  for (const std::string& storage : storageChoices(t)) {
    TechniqueParams p = defaultTechniqueParams();
    if (!storage.empty()) setParam(t, p, "storage", storage);
    variants.push_back(p);
    labels.push_back(storage.empty() ? "default" : storage);
  }
  if (t == Technique::Esm) {
    for (const char* setting :
         {"classifier=zmax", "fallback=paper", "filtering=log", "classifier=none"}) {
      TechniqueParams p = defaultTechniqueParams();
      const std::string s(setting);
      setParam(t, p, s.substr(0, s.find('=')), s.substr(s.find('=') + 1));
      variants.push_back(p);
      labels.push_back(s);
    }
  }
  if (t == Technique::PowerCdf) {
    TechniqueParams p = defaultTechniqueParams();
    setParam(t, p, "layers", "3");
    variants.push_back(p);
    labels.push_back("layers=3");
  }
  if (t == Technique::Lvsm) {  // fixed splits: the CPU twin needs no Lloyd placement of its own
    for (TechniqueParams& p : variants) setParam(t, p, "placement", "uniform");
  }
  for (size_t v = 0; v < variants.size(); ++v) {
    for (FilterMode f : {FilterMode::Point, FilterMode::Bilinear, FilterMode::Trilinear,
                         FilterMode::Anisotropic, FilterMode::SummedArea}) {
      cases.push_back({labels[v] + " " + std::string(filterModeName(f)), variants[v], f});
    }
  }
  return cases;
}

// Pixels whose discrete decision (ESM's classification, LVSM's layer) may take the other branch
// at a tie; and the reference's tie flips (ReferenceParity below).
constexpr double kPixelShare = 0.001;

std::string render(const char* what, const std::string& scene, const std::string& label,
                   const Differences& d) {
  std::ostringstream text;
  text << what << " " << scene << " " << label << ": " << d.values.size() << " pixels, p99.9 "
       << d.quantile(0.999) << ", max " << d.max();
  return text.str();
}

class LookupParity : public testing::GlTest, public ::testing::WithParamInterface<Technique> {};

TEST_P(LookupParity, GpuVisibilityEqualsTheCpuTwinOnEveryScene) {
  gl::Renderer renderer(*context);
  const Technique technique = GetParam();
  int checked = 0;
  for (std::string_view sceneName : builtinSceneNames()) {
    const Scene scene = makeBuiltinScene(sceneName);
    for (const ParityCase& c : casesFor(technique)) {
      gl::RenderSettings s;
      s.lookupInputs = true;  // the test reads the lookup's inputs
      s.technique = technique;
      s.params = c.params;
      s.filter = c.filter;
      s.shadowMapSize = 128;
      s.width = 96;
      s.height = 54;
      s.blur = {BlurKernel::Box, 1, 1.0f};
      s.anisotropy = 8;
      try {
        renderer.validate(s);
      } catch (const Error& e) {
        // Only summed-area tables of exponential or min/max channels are refused.
        EXPECT_EQ(c.filter, FilterMode::SummedArea) << c.label << ": " << e.what();
        continue;
      }
      const gl::RenderResult r = renderer.render(scene, s);
      LayerTwins twins(renderer, r,
                       LookupConfig{technique, r.params, c.filter, s.blur, s.anisotropy,
                                    renderer.halfFloatRounding()});
      const ChannelRounding rounding =
          channelRounding(c.filter, techniqueStorage(technique, r.params));
      Differences d;
      size_t diagnosticMismatches = 0;
      // MSM's Hamburger solve on 32-bit moments (Peters and Klein; its bias alpha = 3e-6) is
      // ill-conditioned where the filtered depths barely spread: there the GPU's own fp32
      // arithmetic in the solve, which moves no channel, moves the visibility by up to 0.4,
      // beyond the channels' rounding envelope. Moving the channels by 2 to 1024 times their
      // rounding reaches the GPU's value: one to three pixels of ~4000 in a case, measured with
      // boxes of 3 to 11 taps, before the box summed its taps at unit weight (at 5 and 7 taps)
      // and after (at 3, 7, 9 and 11); which pixels, and whether any, changes with the box's
      // arithmetic and width. Such a pixel is counted, at most kPixelShare of them, and held to
      // the envelope of the channels moved by 1024 times their rounding (kIllConditioned); every
      // other pixel is held to the envelope itself.
      const bool msmFloat32 = technique == Technique::Msm &&
                              techniqueStorage(technique, r.params) == StorageFormat::Float32;
      constexpr float kIllConditioned = 1024.0f;
      size_t msmOutliers = 0;
      for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
          if (r.lookup.at(x, y, 3) <= 0.0f) continue;  // outside the shadow map
          const LookupPixel pixel = gl::lookupPixelAt(r, x, y);
          const CpuShadowLookup& twin = twins.at(x, y);
          const LookupSample cpu = twin.lookup(pixel);
          const float gpu = r.visibility.at(x, y);
          float error = std::abs(cpu.visibility - gpu);
          if (cpu.diagnostic != r.diagnostic.at(x, y)) {
            // A decision at a tie (ESM's classification of a test within rounding of its
            // threshold, LVSM's layer of a receiver on a split) took the other branch: counted
            // below, not compared.
            ++diagnosticMismatches;
            continue;
          }
          // PCF and the hard test filter after the test; ESM's failing pixels take PCF.
          const bool reconstructed = !filtersAfterTest(technique) && technique != Technique::Hard &&
                                     !(technique == Technique::Esm && cpu.diagnostic > 0.5f);
          if (error > kArithmetic && reconstructed) {
            const Envelope e = roundingEnvelope(technique, twin, r.params, pixel, rounding);
            error = std::max({e.lo - gpu, gpu - e.hi, 0.0f});
            if (error > kArithmetic && msmFloat32) {
              const ChannelRounding wide{kIllConditioned * rounding.relative,
                                         kIllConditioned * rounding.absolute};
              const Envelope w = roundingEnvelope(technique, twin, r.params, pixel, wide);
              error = std::max({w.lo - gpu, gpu - w.hi, 0.0f});
              if (error <= kArithmetic) ++msmOutliers;
            }
          } else if (error > kArithmetic) {
            // A depth test (PCF, the hard test, ESM's fallback): a tap whose depth lies within
            // the receiver-plane depth's rounding of the receiver may flip; the GPU's value must
            // lie between the CPU's for the receiver moved that much either way.
            LookupPixel moved = pixel;
            moved.receiverDepth -= kTieRounding;
            const float front = twin.lookup(moved).visibility;
            moved.receiverDepth += 2.0f * kTieRounding;
            const float behind = twin.lookup(moved).visibility;
            error = std::max({behind - gpu - kArithmetic, gpu - front - kArithmetic, 0.0f});
          }
          d.values.push_back(error);
        }
      }
      std::sort(d.values.begin(), d.values.end());
      ASSERT_GT(d.values.size(), 1000u) << sceneName << ": the scene must fill the frame";
      const std::string where = render("", std::string(sceneName), c.label, d);
      const size_t allowed = size_t(kPixelShare * double(d.values.size()));
      EXPECT_LE(d.max(), kArithmetic) << where;
      // ESM's failure classification and LVSM's layer agree but at ties.
      EXPECT_LE(diagnosticMismatches, allowed) << where << ", diagnostic mismatches";
      EXPECT_LE(msmOutliers, allowed) << where << ", outliers of MSM's fp32 solve";
      ++checked;
    }
  }
  EXPECT_GE(checked, int(builtinSceneNames().size()));
}

// fp32 sums of up to a few thousand weighted taps, rounded in different orders.
constexpr float kSumRounding = 1e-5f;

TEST_F(ReferenceParity, GpuFilteredReferenceEqualsTheCpuTwinsOnEveryScene) {
  gl::Renderer renderer(*context);
  for (std::string_view sceneName : builtinSceneNames()) {
    const Scene scene = makeBuiltinScene(sceneName);
    for (FilterMode f : {FilterMode::Point, FilterMode::Bilinear, FilterMode::Trilinear,
                         FilterMode::Anisotropic, FilterMode::SummedArea}) {
      gl::RenderSettings s;
      s.lookupInputs = true;  // the test reads the lookup's inputs
      s.technique = Technique::Pcf;
      s.filter = f;
      s.shadowMapSize = 128;
      s.width = 96;
      s.height = 54;
      s.blur = {BlurKernel::Gaussian, 2, 1.0f};
      s.anisotropy = 8;
      const gl::RenderResult r = renderer.renderReference(scene, s, 1);
      LayerTwins twins(renderer, r,
                       LookupConfig{Technique::Pcf, r.params, f, s.blur, s.anisotropy});
      Differences d;
      for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
          if (r.lookup.at(x, y, 3) <= 0.0f) continue;
          // The two sides sum the same fp32 weights, but a tap whose depth lies within fp32
          // rounding of the tie tolerance may flip: the GPU's value must then lie between the
          // CPU's for the receiver moved by kTieRounding either way (more lit in front).
          LookupPixel px = gl::lookupPixelAt(r, x, y);
          const CpuShadowLookup& twin = twins.at(x, y);
          const float cpu = twin.referenceVisibility(px);
          const float gpu = r.visibility.at(x, y);
          float error = std::abs(cpu - gpu);
          if (error > kSumRounding) {
            px.receiverDepth -= kTieRounding;
            const float front = twin.referenceVisibility(px);
            px.receiverDepth += 2.0f * kTieRounding;
            const float behind = twin.referenceVisibility(px);
            if (gpu >= behind - kSumRounding && gpu <= front + kSumRounding) error = 0.0f;
          }
          d.values.push_back(error);
        }
      }
      std::sort(d.values.begin(), d.values.end());
      EXPECT_LE(d.max(), kSumRounding)
          << render("reference", std::string(sceneName), std::string(filterModeName(f)), d);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllTechniques, LookupParity, ::testing::ValuesIn(allTechniques()),
                         [](const ::testing::TestParamInfo<Technique>& param) {
                           return std::string(techniqueId(param.param));
                         });

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The minification scene's far posts under trilinear lookups at 1024^2: kernels of hundreds of
// thousands of texel tests, beyond what one shader invocation may run.
gl::RenderSettings wideMinifiedKernels(int width, int height) {
  gl::RenderSettings s;
  s.technique = Technique::Pcf;
  s.filter = FilterMode::Trilinear;
  s.shadowMapSize = 1024;
  s.width = width;
  s.height = height;
  s.blur = {BlurKernel::Box, 2, 1.0f};
  return s;
}

TEST_F(ReferenceParity, WideMinifiedKernelsAreNeverTruncatedByTheDriver) {
  // Trilinear lookups of the far posts at 1024^2 reach mip levels whose kernels need hundreds of
  // thousands of texel tests; llvmpipe ends an invocation's loops after 65535 iterations and
  // returns whatever was summed (3% of these pixels were off by up to 0.44). The camera pass
  // leaves such pixels to the CPU twin: every pixel must equal the CPU reference.
  gl::Renderer renderer(*context);
  gl::RenderSettings s = wideMinifiedKernels(160, 90);
  s.lookupInputs = true;  // the test reads the lookup's inputs
  const gl::RenderResult r = renderer.renderReference(makeBuiltinScene("minification"), s, 1);
  const CpuShadowLookup twin(renderer.readDepthMap(),
                             {Technique::Pcf, r.params, s.filter, s.blur, s.anisotropy});
  Differences d;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      if (r.lookup.at(x, y, 3) <= 0.0f) continue;
      d.values.push_back(
          std::abs(twin.referenceVisibility(gl::lookupPixelAt(r, x, y)) - r.visibility.at(x, y)));
    }
  }
  std::sort(d.values.begin(), d.values.end());
  ASSERT_GT(d.values.size(), 5000u);
  // The same sums on both sides but for rounding and ties (see the test above): 1e-3.
  EXPECT_LE(d.quantile(1.0 - kPixelShare), 1e-3f)
      << render("reference", "minification", "trilinear", d);
}

// A supersampled reference reads its lookup's inputs back only when the CPU has pixels to
// complete from them (Renderer::completeReferenceOnCpu); the far posts at 1024^2 give it such
// pixels, and it must average the same completed frame the full-size reference returns.
TEST_F(ReferenceParity, ASupersampledReferenceCompletesItsPixelsAsTheFullSizeOneDoes) {
  gl::Renderer renderer(*context);
  const gl::RenderSettings s = wideMinifiedKernels(80, 45);
  const Scene scene = makeBuiltinScene("minification");
  const Image averaged = renderer.renderReference(scene, s, 2).visibility;
  gl::RenderSettings big = s;
  big.width = 2 * s.width;
  big.height = 2 * s.height;
  const Image full = renderer.renderReference(scene, big, 1).visibility;
  int differing = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      // The same four floats summed in the same order: equal to the last bit.
      const float mean = (full.at(2 * x, 2 * y) + full.at(2 * x + 1, 2 * y) +
                          full.at(2 * x, 2 * y + 1) + full.at(2 * x + 1, 2 * y + 1)) /
                         4.0f;
      differing += std::abs(averaged.at(x, y) - mean) > 1e-6f;
    }
  }
  EXPECT_EQ(differing, 0);
}

// compare's ground truth reads back only its visibility: the pixels left to the CPU are then
// shaded from a colour and light amount the frame did not read back, so the completion reads
// them itself; the visibility is the full read-back's to the last bit (the same frame), and the
// images not asked for stay empty.
TEST_F(ReferenceParity, AReferenceReadingOnlyItsVisibilityCompletesItsPixelsTheSame) {
  gl::Renderer renderer(*context);
  const gl::RenderSettings s = wideMinifiedKernels(80, 45);
  const Scene scene = makeBuiltinScene("minification");
  // The sub-pixels' frame, to count the pixels left to the CPU: the test needs some.
  gl::RenderSettings big = s;
  big.width = 2 * s.width;
  big.height = 2 * s.height;
  const gl::RenderResult subPixels = renderer.renderReference(scene, big, 1);
  const CpuShadowLookup twin(renderer.readDepthMap(),
                             {Technique::Pcf, subPixels.params, s.filter, s.blur, s.anisotropy});
  int leftToCpu = 0;
  for (int y = 0; y < big.height; ++y) {
    for (int x = 0; x < big.width; ++x) {
      leftToCpu += subPixels.lookup.at(x, y, 3) > 0.0f &&
                   twin.referenceLeftToCpu(gl::lookupPixelAt(subPixels, x, y));
    }
  }
  EXPECT_GT(leftToCpu, 10);
  const gl::RenderResult everything = renderer.renderReference(scene, s, 2);
  gl::RenderSettings visibilityOnly = s;
  visibilityOnly.readBack = gl::frame_image::kVisibility;
  const gl::RenderResult r = renderer.renderReference(scene, visibilityOnly, 2);
  EXPECT_TRUE(r.color.empty());
  EXPECT_TRUE(r.diagnostic.empty());
  ASSERT_FALSE(everything.color.empty());
  ASSERT_EQ(r.visibility.data().size(), everything.visibility.data().size());
  int differing = 0;
  for (size_t i = 0; i < r.visibility.data().size(); ++i) {
    differing += r.visibility.data()[i] != everything.visibility.data()[i];
  }
  EXPECT_EQ(differing, 0);
}

}  // namespace
}  // namespace penumbra
