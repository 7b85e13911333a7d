// The GPU pipeline against the CPU reference and the papers: encode, blur, mips and summed-area
// tables equal the reference filters; every scene renders with every technique; VSM equals
// same-kernel PCF on the planar scene; VSM bleeds on the bench scene where EVSM4 does not;
// shading is Lambert plus ambient; memory is texels times texel bytes, as in the ESM paper.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "gl_test_context.h"
#include "penumbra/error.h"
#include "penumbra/filters.h"
#include "penumbra/gl/renderer.h"
#include "penumbra/gl/scene_buffers.h"
#include "penumbra/metrics.h"
#include "penumbra/params.h"
#include "penumbra/shared/channel_reduction.h"
#include "penumbra/shared/shadow_lookup.h"
#include "penumbra/storage_format.h"
#include "penumbra/summed_area_table.h"

namespace penumbra {
namespace {

class RendererTest : public testing::GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (context) renderer = std::make_unique<gl::Renderer>(*context);
  }

  gl::RenderSettings small(Technique t) const {
    gl::RenderSettings s;
    s.lookupInputs = true;  // the tests read the lookup's inputs
    s.technique = t;
    s.shadowMapSize = 256;
    s.width = 160;
    s.height = 90;
    return s;
  }

  // A light-space depth map of a real scene, 128^2.
  Image sceneDepth() {
    gl::RenderSettings s = small(Technique::Hard);
    s.shadowMapSize = 128;
    renderer->render(makeBuiltinScene("backyard"), s);
    return renderer->readDepthMap();
  }

  std::unique_ptr<gl::Renderer> renderer;
};

// The CPU reference of encode -> blur -> mip chain, rounding to storage wherever the GPU stores.
std::vector<Image> referenceChain(const Image& depth, const gl::RenderSettings& s) {
  const StorageFormat storage = techniqueStorage(s.technique, s.params);
  const int channels = channelCount(s.technique, s.params);
  auto quantize = [&](Image image) {
    for (float& v : image.data()) v = quantizeToStorage(v, storage);
    return image;
  };
  Image encoded(depth.width(), depth.height(), channels);
  std::vector<float> texel(static_cast<size_t>(channels), 0.0f);
  for (int y = 0; y < depth.height(); ++y) {
    for (int x = 0; x < depth.width(); ++x) {
      encodeDepth(s.technique, s.params, depth.at(x, y), texel);
      for (int c = 0; c < channels; ++c) encoded.at(x, y, c) = texel[size_t(c)];
    }
  }
  std::vector<ChannelReduction> reductions;
  for (int c = 0; c < channels; ++c)
    reductions.push_back(channelReduction(s.technique, s.params, c));
  const float c = s.params.esm.exponent;
  Image level = quantize(separableFilter(quantize(encoded), s.blur, reductions, c,
                                         alikeTapsFor(s.technique, s.params)));
  std::vector<Image> chain{level};
  while (chain.back().width() > 1)
    chain.push_back(quantize(reduceMipLevel(chain.back(), reductions, c)));
  return chain;
}

// Storage rounding, twice (the GPU also stores the blur's intermediate axis), plus fp32 noise.
float tolerance(StorageFormat storage, float value) {
  switch (storage) {
    case StorageFormat::Float16: return 4e-3f * std::max(1.0f, std::abs(value));  // 4 ulps
    case StorageFormat::Unorm16: return 3.0f / 65535.0f;
    case StorageFormat::Unorm8: return 3.0f / 255.0f;
    case StorageFormat::Float32: break;
  }
  return 2e-5f * std::max(1.0f, std::abs(value));
}

// The top-left size x size texels of a depth map.
Image cropped(const Image& depth, int size) {
  Image c(size, size, 1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) c.at(x, y, 0) = depth.at(x, y, 0);
  }
  return c;
}

TEST_F(RendererTest, BoxOverExponentialChannelsStaysFiniteAtTheLargestExponents) {
  // ESM filtering linearly stores exp(c z) up to exp(88) = 1.65e38 and EVSM's second moment
  // exp(2 * 42) = 3.0e36: a box over them must weigh each tap before adding it (alikeTapsFor),
  // since 3 taps of exp(88) or 113 of exp(84) summed first pass fp32's largest value, 3.4e38, and
  // a compiler that sees one weight on every tap may regroup the weighted sum into w * (a + b + c):
  // reading weights[0] for every tap overflowed here
  // (docs/results/passes-llvmpipe-2026-12-06-rows.md). EVSM4's fused case (21 taps at most) cannot
  // overflow and checks the values only. Over a map at the far plane every box mean is the stored
  // value; the tolerance is the parity tests' for the GPU's own exponentials in fp32, 2e-5 relative
  // (the GPU's exp against the CPU's, squared for EVSM's second moment, and the taps' roundings).
  Image depth(64, 64, 1);
  for (float& v : depth.data()) v = 1.0f;
  struct Case {
    Technique technique;
    const char* param;
    int radius;
    bool fused;
  };
  for (const Case& k :
       {Case{Technique::Esm, "c=88", 1, false}, Case{Technique::Esm, "c=88", 1, true},
        Case{Technique::Esm, "c=88", 64, false}, Case{Technique::Evsm4, "cPositive=42", 64, false},
        Case{Technique::Evsm4, "cPositive=42", 10, true},
        Case{Technique::Evsm2, "cPositive=42", 64, false}}) {
    gl::RenderSettings s = small(k.technique);
    const std::vector<Technique> one{k.technique};
    applyParamAssignment(one, s.params, k.param);
    s.filter = gl::FilterMode::Bilinear;
    s.blur = BlurSpec{BlurKernel::Box, k.radius, 1.0f};
    s.fusePrefilter = k.fused;
    renderer->filterDepthMap(depth, s);
    const Image gpu = renderer->readChannels(0);
    const float stored = k.technique == Technique::Esm ? std::exp(88.0f) : std::exp(84.0f);
    int bad = 0;
    for (size_t i = 0; i < gpu.data().size(); ++i) {
      const float v = gpu.data()[i];
      // ESM's one channel and EVSM's second moment hold exp(88) and exp(84).
      const bool largest = k.technique == Technique::Esm || i % size_t(gpu.channels()) == 1;
      if (!std::isfinite(v) || (largest && std::abs(v - stored) > 2e-5f * stored)) {
        if (++bad <= 3) {
          ADD_FAILURE() << techniqueId(k.technique) << " " << k.param << " radius " << k.radius
                        << (k.fused ? " fused" : "") << " value " << i << ": " << v;
        }
      }
    }
    EXPECT_EQ(bad, 0);
  }
}

TEST_F(RendererTest, EncodeBlurAndMipsMatchTheCpuReference) {
  const Image scene = sceneDepth();
  // A power of two (every level halves) and 100 (levels of 25 and 3 texels fold their odd
  // row and column into the last block: shared/mip_span.h).
  for (const Image& depth : {scene, cropped(scene, 100)}) {
    struct Case {
      Technique technique;
      const char* param;  // NAME=VALUE applied on top of the defaults, or nullptr
    };
    // Both kernels: a Gaussian weighs each tap, a box sums its taps and scales once
    // (shared/channel_reduction.h scaleTapWeights).
    for (const BlurSpec& blur :
         {BlurSpec{BlurKernel::Gaussian, 2, 1.0f}, BlurSpec{BlurKernel::Box, 2, 1.0f}})
      for (const Case& k :
           {Case{Technique::Vsm, nullptr}, Case{Technique::Vsm, "storage=unorm16"},
            Case{Technique::Evsm4, nullptr}, Case{Technique::Evsm4, "storage=float16"},
            Case{Technique::Esm, nullptr}, Case{Technique::Esm, "filtering=log"},
            Case{Technique::Msm, nullptr}, Case{Technique::Msm, "storage=float32"},
            Case{Technique::PowerCdf, nullptr}, Case{Technique::PowerCdf, "layers=3"},
            Case{Technique::Csm, nullptr}, Case{Technique::Csm, "storage=float32"},
            Case{Technique::Lvsm, nullptr}}) {
        gl::RenderSettings s = small(k.technique);
        s.filter = gl::FilterMode::Trilinear;
        s.blur = blur;
        if (k.param != nullptr) {
          const std::vector<Technique> one{k.technique};
          applyParamAssignment(one, s.params, k.param);
        }
        renderer->filterDepthMap(depth, s);
        const std::vector<Image> reference = referenceChain(depth, s);
        const StorageFormat storage = techniqueStorage(k.technique, s.params);
        ASSERT_EQ(renderer->channelMipLevels(), int(reference.size()));
        // A box summed at unit weight over channels whose encode is exact on both sides
        // (polynomials of depth: VSM, MSM, the power CDF; CSM's sines and cosines by polynomial
        // and its walk, precise multiplies and adds, its depth scale a division by a power of two
        // at the defaults: with GLSL's fma, which llvmpipe rounds twice and std::fma once, they
        // part by an ulp) and stored in fp32 adds the same floats
        // in the same order and scales once: the CPU's bits, in every level (a halving mip level
        // sums four exact products in order: EachMipLevelIsTheCpuReductionOfTheGpuLevelAboveIt).
        const bool sameBits = storage == StorageFormat::Float32 &&
                              sumsTapsAtUnitWeight(blur, alikeTapsFor(k.technique, s.params)) &&
                              (k.technique == Technique::Vsm || k.technique == Technique::Msm ||
                               k.technique == Technique::PowerCdf || k.technique == Technique::Csm);
        auto allowed = [&](float expected) {
          return sameBits ? 0.0f : tolerance(storage, expected);
        };
        for (int level : {0, 1, int(reference.size()) - 1}) {
          const Image gpu = renderer->readChannels(level);
          const Image& cpu = reference[size_t(level)];
          ASSERT_EQ(gpu.channels(), cpu.channels());
          int bad = 0;
          for (size_t i = 0; i < gpu.data().size(); ++i) {
            const float expected = cpu.data()[i];
            if (std::abs(gpu.data()[i] - expected) > allowed(expected) && ++bad <= 3) {
              ADD_FAILURE() << depth.width() << "^2 " << techniqueId(k.technique)
                            << (k.param ? k.param : "")
                            << (blur.kernel == BlurKernel::Box ? " box" : " gaussian") << " level "
                            << level << " value " << i << ": gpu " << gpu.data()[i] << " cpu "
                            << expected;
            }
          }
          EXPECT_EQ(bad, 0) << depth.width();
        }
      }
  }
}

// One step of `storage` at `value`: a unorm code, a half's ulp, nothing for fp32.
float storageStep(StorageFormat storage, float value) {
  switch (storage) {
    case StorageFormat::Unorm16: return 1.0f / 65535.0f;
    case StorageFormat::Unorm8: return 1.0f / 255.0f;
    case StorageFormat::Float16: return std::max(std::abs(value), 6.1e-5f) / 1024.0f;
    case StorageFormat::Float32: break;
  }
  return 0.0f;
}

// Each mip level is the CPU's reduction (reduceMipLevel) of the GPU's level above it, rounded to
// storage once, for every technique (EVSM4, CSM and VSM in two storages each, ESM in both filter
// spaces, the power CDF with one and three layers) at a power of two and at 100 (levels of 25
// and 3 texels fold their odd row and column into the last block). The pass reads whole texels
// and reduces them in the CPU's order, so:
// - a halving level weighs four texels by 1/4, each product exact and the sums in the CPU's
//   order: the same float on any GPU that keeps the order GLSL writes (a min or max is the same
//   texel). Unorm means of four codes often land exactly between two codes, and GL leaves such
//   ties to the implementation (llvmpipe rounds them to even, as quantizeToStorage does): a tie
//   may take either code;
// - an odd level weighs six or nine texels by 1/6 or 1/9, which GLSL may divide within 2.5 ulps
//   and fuse into the sums: 4 ulps, which rounding to storage can turn into one step;
// - ESM's log-space mean takes the GPU's own exp and log: 4 ulps.
// On llvmpipe every texel is exact, ties and odd levels included.
TEST_F(RendererTest, EachMipLevelIsTheCpuReductionOfTheGpuLevelAboveIt) {
  const Image scene = sceneDepth();
  for (const Image& depth : {scene, cropped(scene, 100)}) {
    for (const auto& [technique, param] :
         std::vector<std::pair<Technique, const char*>>{{Technique::Vsm, nullptr},
                                                        {Technique::Vsm, "storage=unorm16"},
                                                        {Technique::Evsm2, nullptr},
                                                        {Technique::Evsm4, nullptr},
                                                        {Technique::Evsm4, "storage=float16"},
                                                        {Technique::Esm, nullptr},
                                                        {Technique::Esm, "filtering=log"},
                                                        {Technique::Msm, nullptr},
                                                        {Technique::PowerCdf, nullptr},
                                                        {Technique::PowerCdf, "layers=3"},
                                                        {Technique::Csm, nullptr},
                                                        {Technique::Csm, "storage=float32"},
                                                        {Technique::Lvsm, nullptr}}) {
      gl::RenderSettings s = small(technique);
      s.filter = gl::FilterMode::Trilinear;
      s.blur = {BlurKernel::Gaussian, 2, 1.0f};
      if (param != nullptr) {
        const std::vector<Technique> one{technique};
        applyParamAssignment(one, s.params, param);
      }
      renderer->filterDepthMap(depth, s);
      const StorageFormat storage = techniqueStorage(technique, s.params);
      const bool unorm = storage == StorageFormat::Unorm8 || storage == StorageFormat::Unorm16;
      const bool logSpace =
          technique == Technique::Esm && s.params.esm.filterSpace == shaders::kEsmFilterLog;
      std::vector<ChannelReduction> reductions;
      for (int c = 0; c < channelCount(technique, s.params); ++c) {
        reductions.push_back(channelReduction(technique, s.params, c));
      }
      const HalfRounding rounding = renderer->halfFloatRounding();
      int bad = 0;
      for (int level = 0; level + 1 < renderer->channelMipLevels(); ++level) {
        const Image above = renderer->readChannels(level);
        const bool halving = above.width() % 2 == 0;
        const Image exact = reduceMipLevel(above, reductions, s.params.esm.exponent);
        // Read back as floats: unorm codes convert by the device's own arithmetic (198/255 may
        // read 0.77647066 where the CPU divides to 0.7764706), so both sides are compared as codes.
        Image gpu = renderer->readChannels(level + 1);
        for (float& v : gpu.data()) v = quantizeToStorage(v, storage, rounding);
        ASSERT_EQ(gpu.data().size(), exact.data().size());
        for (size_t i = 0; i < gpu.data().size(); ++i) {
          const float raw = exact.data()[i];
          const float want = quantizeToStorage(raw, storage, rounding);
          const float codes = raw * (storage == StorageFormat::Unorm8 ? 255.0f : 65535.0f);
          const bool tie = unorm && codes - std::floor(codes) == 0.5f;
          const float ulps = 4.0f * 1.2e-7f * std::abs(want);
          float allowed = 0.0f;
          if (logSpace) allowed = ulps;
          if (!halving) allowed = ulps + storageStep(storage, want);
          if (tie) allowed = std::max(allowed, storageStep(storage, want));
          if (!(std::abs(gpu.data()[i] - want) <= allowed) && ++bad <= 3) {
            ADD_FAILURE() << depth.width() << "^2 " << techniqueId(technique)
                          << (param ? param : "") << " level " << level + 1 << " of "
                          << above.width() << "^2 value " << i << ": gpu " << gpu.data()[i]
                          << " cpu " << want << " (unrounded " << raw << ")";
          }
        }
      }
      EXPECT_EQ(bad, 0) << depth.width() << "^2 " << techniqueId(technique);
    }
  }
}

// Every cascade's mips reduce each channel by its own reduction: the power CDF's min and max
// channels stay min and max in the last cascade too, with one texel layer (reductions resolved
// at compile time) and with several (resolved per texel from the channel within its cascade).
TEST_F(RendererTest, MipsOfEveryCascadeReduceEachChannelByItsReduction) {
  const Scene scene = makeBuiltinScene("street");
  for (const char* layers : {"layers=1", "layers=2"}) {
    gl::RenderSettings s = small(Technique::PowerCdf);
    s.shadowMapSize = 64;
    s.filter = gl::FilterMode::Trilinear;
    s.cascades.count = 3;
    const std::vector<Technique> one{Technique::PowerCdf};
    applyParamAssignment(one, s.params, layers);
    renderer->render(scene, s);
    const int channels = channelCount(Technique::PowerCdf, s.params);
    std::vector<ChannelReduction> reductions;
    for (int c = 0; c < channels; ++c) {
      reductions.push_back(channelReduction(Technique::PowerCdf, s.params, c));
    }
    const Image base = renderer->readChannels(0, 2);
    const Image expected = reduceMipLevel(base, reductions);
    const Image gpu = renderer->readChannels(1, 2);
    ASSERT_EQ(gpu.channels(), expected.channels());
    int bad = 0;
    for (size_t i = 0; i < gpu.data().size(); ++i) {
      // fp32 storage, a halving level: min and max are the same texel, the mean the same four
      // exact products summed in the CPU's order
      // (EachMipLevelIsTheCpuReductionOfTheGpuLevelAboveIt).
      if (gpu.data()[i] != expected.data()[i] && ++bad <= 3) {
        ADD_FAILURE() << layers << " value " << i << " (channel " << i % size_t(channels)
                      << "): gpu " << gpu.data()[i] << " cpu " << expected.data()[i];
      }
    }
    EXPECT_EQ(bad, 0) << layers;
  }
}

TEST_F(RendererTest, SummedAreaTableMatchesTheCpuReference) {
  const Image depth = sceneDepth();
  gl::RenderSettings s = small(Technique::Vsm);
  s.filter = gl::FilterMode::SummedArea;
  renderer->filterDepthMap(depth, s);
  const Image encoded = renderer->readChannels(0);
  const SummedAreaTable cpu(encoded);
  for (auto [x0, y0, x1, y1] :
       {std::array{0, 0, 0, 0}, std::array{3, 5, 9, 40}, std::array{0, 0, 127, 127},
        std::array{60, 61, 127, 100}, std::array{17, 17, 17, 17}}) {
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(renderer->summedAreaBoxMean(x0, y0, x1, y1, c), cpu.boxMean(x0, y0, x1, y1, c),
                  2.0 * cpu.errorBound(c) + 1e-9)
          << x0 << "," << y0 << " " << x1 << "," << y1 << " channel " << c;
    }
  }
}

// The quantisation depends only on each channel's extremes (shared/summed_area.h), which the
// GPU's atomics reach in any order, and rounds ties to even on both sides: the GPU table holds
// the CPU table's bits, so every box mean is the same double. Depths u^8 (u uniform) put many
// texels far below their channel's range, where the fixed-point step is coarser than the float's
// own and quantising rounds (a scene's depths all lie within 2^9 of the range and quantise
// exactly, whatever the centre).
TEST_F(RendererTest, SummedAreaTableHoldsTheCpuTablesBits) {
  Image depth(128, 128, 1);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (float& z : depth.data()) z = std::pow(unit(rng), 8.0f);
  for (Technique t : {Technique::Vsm, Technique::Msm}) {
    gl::RenderSettings s = small(t);
    s.filter = gl::FilterMode::SummedArea;
    renderer->filterDepthMap(depth, s);
    const Image encoded = renderer->readChannels(0);
    const SummedAreaTable cpu(encoded);
    for (auto [x0, y0, x1, y1] :
         {std::array{0, 0, 0, 0}, std::array{3, 5, 9, 40}, std::array{0, 0, 127, 127},
          std::array{60, 61, 127, 100}, std::array{17, 17, 17, 17}, std::array{127, 0, 127, 127}}) {
      for (int c = 0; c < encoded.channels(); ++c) {
        EXPECT_EQ(renderer->summedAreaBoxMean(x0, y0, x1, y1, c), cpu.boxMean(x0, y0, x1, y1, c))
            << techniqueId(t) << " " << x0 << "," << y0 << " " << x1 << "," << y1 << " channel "
            << c;
      }
    }
  }
}

// The extremes pass reads every row, four at a time and then the rows left over
// (passes/sat_stats.comp): the GPU derives the CPU table's quantisation of each channel (centre
// and step, shared/summed_area.h) from a map whose only lowest or highest depth lies in the
// row of any of an iteration's four reads or in a leftover row (130 = 4 * 32 + 2). The other depths
// lie within [0.40, 0.45], so the planted one alone sets that end of the range.
TEST_F(RendererTest, SummedAreaTableFindsAnExtremeInAnyRow) {
  constexpr int kSize = 130;
  struct Planted {
    int x, y;
    float depth;
  };
  // Rows 4 to 7: each of an iteration's four reads.
  for (const Planted planted :
       {Planted{3, 4, 0.9f}, Planted{50, 5, 0.1f}, Planted{90, 6, 0.9f}, Planted{77, 7, 0.1f},
        Planted{5, kSize - 1, 0.9f}, Planted{64, kSize - 2, 0.1f}}) {
    Image depth(kSize, kSize, 1);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> band(0.40f, 0.45f);
    for (float& z : depth.data()) z = band(rng);
    depth.at(planted.x, planted.y, 0) = planted.depth;
    gl::RenderSettings s = small(Technique::Vsm);
    s.filter = gl::FilterMode::SummedArea;
    renderer->filterDepthMap(depth, s);
    const SummedAreaTable cpu(renderer->readChannels(0));
    for (int c = 0; c < 2; ++c) {
      const gl::Renderer::SummedAreaChannelStats gpu = renderer->summedAreaQuantisation(c);
      EXPECT_EQ(gpu.centre, cpu.centre(c)) << planted.depth << " at row " << planted.y << ", "
                                           << "channel " << c;
      EXPECT_EQ(gpu.step, cpu.step(c)) << planted.depth << " at row " << planted.y << ", "
                                       << "channel " << c;
    }
  }
}

TEST_F(RendererTest, EverySceneRendersWithEveryTechniqueWithoutNanOrGlErrors) {
  for (std::string_view name : builtinSceneNames()) {
    const Scene scene = makeBuiltinScene(name);
    for (Technique t : allTechniques()) {
      gl::RenderSettings s = small(t);
      if (t == Technique::Vsm && name == "contact") s.filter = gl::FilterMode::SummedArea;
      if (t == Technique::Msm && name == "spheres") s.msaaSamples = 4;
      const gl::RenderResult r = renderer->render(scene, s);
      int outOfRange = 0;
      for (float v : r.visibility.data()) outOfRange += !(v >= 0.0f && v <= 1.0f);  // and NaN
      EXPECT_EQ(outOfRange, 0) << name << " " << techniqueId(t);
    }
  }
}

// The camera pass shades albedo * (ambient + (1 - ambient) * N.L * visibility). On the planar
// scene the light falls straight down, so the ground (N.L = 1, the farthest receiver from the
// light) reads albedo * (ambient + (1 - ambient) * v) wherever v is, lit, penumbra or shadow: in
// linear light (an sRGB encode here would put the lit ground at 0.89 for 0.75). The colour target
// is RGBA16F: a value below 1 is stored within one fp16 step, 2^-11, whether the device rounds to
// nearest or toward zero (llvmpipe).
TEST_F(RendererTest, GroundColourIsAlbedoTimesAmbientPlusLambertTimesVisibility) {
  const Scene scene = makeBuiltinScene("planar");
  const glm::vec3 albedo = scene.meshes.front().albedo;  // the ground comes first
  gl::RenderSettings s = small(Technique::Pcf);
  s.ambient = 0.3f;
  const gl::RenderResult r = renderer->render(scene, s);
  float groundDepth = 0.0f;  // the largest receiver depth on a surface facing the light
  for (int y = 0; y < r.lookup.height(); ++y) {
    for (int x = 0; x < r.lookup.width(); ++x) {
      if (r.lookup.at(x, y, 3) == 1.0f) groundDepth = std::max(groundDepth, r.lookup.at(x, y, 2));
    }
  }
  int lit = 0, penumbra = 0, shadowed = 0, bad = 0;
  for (int y = 0; y < r.lookup.height(); ++y) {
    for (int x = 0; x < r.lookup.width(); ++x) {
      if (r.lookup.at(x, y, 3) != 1.0f || r.lookup.at(x, y, 2) < groundDepth - 1e-3f) continue;
      const float v = r.visibility.at(x, y);
      lit += v == 1.0f;
      shadowed += v == 0.0f;
      penumbra += v > 0.0f && v < 1.0f;
      for (int c = 0; c < 3; ++c) {
        const float expected = albedo[c] * (s.ambient + (1.0f - s.ambient) * v);
        if (std::abs(r.color.at(x, y, c) - expected) > 0x1.0p-11f && ++bad <= 3) {
          ADD_FAILURE() << "pixel " << x << "," << y << " channel " << c << ": colour "
                        << r.color.at(x, y, c) << ", expected " << expected << " at visibility "
                        << v;
        }
      }
    }
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(lit, 1000);
  EXPECT_GT(shadowed, 100);
  EXPECT_GT(penumbra, 50);
}

// --overlay cascades (compiled into the camera pass, CASCADE_OVERLAY): every pixel's albedo is
// tinted by its cascade's colour, mixed with the next cascade's in the blend band, so that its
// shading is the plain frame's times the tint.
TEST_F(RendererTest, CascadeOverlayTintsEachPixelByItsCascade) {
  const Scene scene = makeBuiltinScene("backyard");
  gl::RenderSettings s = small(Technique::Hard);
  s.cascades.count = 2;
  namespace fi = gl::frame_image;
  s.readBack = fi::kColor | fi::kCascades;
  const gl::RenderResult plain = renderer->render(scene, s);
  s.overlay = gl::Overlay::Cascades;
  const gl::RenderResult tinted = renderer->render(scene, s);
  const glm::vec3 tints[3] = {
      {1.0f, 0.45f, 0.45f}, {0.45f, 1.0f, 0.45f}, {0.5f, 0.6f, 1.0f}};  // camera.frag's
  int seen[2] = {0, 0};
  int blended = 0;
  int wrong = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      // -1: no lookup (the sky, or beyond the map): the read-back names no cascade there, though
      // the shader tints by the depth range alone.
      const int cascade = int(plain.cascades.at(x, y, 0));
      if (cascade < 0) continue;
      const float blend = plain.cascades.at(x, y, 1);
      const glm::vec3 tint = glm::mix(tints[cascade], tints[cascade + 1], blend);
      for (int c = 0; c < 3; ++c) {
        const float expected = plain.color.at(x, y, c) * tint[c];
        // Both colours in RGBA16F: half a step each (2^-11 relative, rounding to nearest) and
        // the product's and the mix's fp32 rounding.
        if (std::abs(tinted.color.at(x, y, c) - expected) > 0x1.0p-10f * expected + 1e-6f) ++wrong;
      }
      ++seen[cascade];
      if (blend > 0.0f) ++blended;
    }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(seen[0], s.width * s.height / 20) << "the view must show the first cascade";
  EXPECT_GT(seen[1], s.width * s.height / 20) << "the view must show the second cascade";
  EXPECT_GT(blended, s.width) << "the view must show the blend band";
}

// The result's parameters are the ones used: fp16 storage clamps EVSM's exponents to what it
// holds (5.54), and the report and render record must not show the 40 that was asked for.
TEST_F(RendererTest, ReportedEvsmExponentsAreTheClampedOnesTheShadersUse) {
  const Scene scene = makeBuiltinScene("planar");
  gl::RenderSettings s = small(Technique::Evsm4);
  s.shadowMapSize = 128;
  s.width = 64;
  s.height = 36;
  s.params.evsm.positiveExponent = 40.0f;
  s.params.evsm.negativeExponent = 5.0f;
  s.params.evsm.storage = shaders::kStorageFloat16;
  const TechniqueParams used = renderer->render(scene, s).params;
  EXPECT_EQ(used.evsm.positiveExponent, shaders::kEvsmMaxExponentFloat16);
  EXPECT_EQ(used.evsm.negativeExponent, 5.0f);  // within fp16's range: as given
  s.params.evsm.storage = shaders::kStorageFloat32;
  EXPECT_EQ(renderer->render(scene, s).params.evsm.positiveExponent, 40.0f);
}

TEST_F(RendererTest, PlanarVsmEqualsPcfWithTheSameKernel) {
  const Scene scene = makeBuiltinScene("planar");
  // VSM box-blurred over 5 taps and fetched bilinearly covers exactly the bilinear-weighted 5x5
  // PCF kernel (thesis §3.2: exact for a planar occluder over a planar receiver).
  gl::RenderSettings vsm = small(Technique::Vsm);
  vsm.shadowMapSize = 512;
  vsm.width = 480;
  vsm.height = 270;
  vsm.blur = {BlurKernel::Box, 2, 1.0f};
  vsm.filter = gl::FilterMode::Bilinear;
  gl::RenderSettings pcf = vsm;
  pcf.technique = Technique::Pcf;
  pcf.params.pcf.kernel = shaders::kKernelBilinear;
  pcf.params.pcf.radius = 2;
  pcf.params.pcf.receiverPlane = 0;
  pcf.params.pcf.bias.constantBias = 1e-4f;  // only against rounding between the two passes
  pcf.params.pcf.bias.slopeScaledBias = 0.0f;
  const Image a = renderer->render(scene, vsm).visibility;
  const Image b = renderer->render(scene, pcf).visibility;
  float worst = 0.0f;
  int penumbra = 0;
  for (size_t i = 0; i < a.data().size(); ++i) {
    worst = std::max(worst, std::abs(a.data()[i] - b.data()[i]));
    penumbra += b.data()[i] > 0.05f && b.data()[i] < 0.95f;
  }
  EXPECT_LT(worst, 1e-3f);
  EXPECT_GT(penumbra, 50) << "the comparison must cover penumbra pixels";
}

TEST_F(RendererTest, BenchVsmBleedsWherePcfIsDarkAndEvsm4BleedsFarLess) {
  const Scene scene = makeBuiltinScene("bench");
  gl::RenderSettings s = small(Technique::Pcf);
  s.shadowMapSize = 512;
  s.width = 480;
  s.height = 270;
  s.blur = {BlurKernel::Box, 3, 1.0f};
  s.filter = gl::FilterMode::Bilinear;
  s.params.pcf.radius = 3;
  const Image pcf = renderer->render(scene, s).visibility;
  s.technique = Technique::Vsm;
  const Image vsm = renderer->render(scene, s).visibility;
  s.technique = Technique::Evsm4;
  const Image evsm = renderer->render(scene, s).visibility;
  double vsmLight = 0.0, evsmLight = 0.0;
  int dark = 0;
  for (size_t i = 0; i < pcf.data().size(); ++i) {
    if (pcf.data()[i] > 0.02f) continue;
    ++dark;
    vsmLight += vsm.data()[i];
    evsmLight += evsm.data()[i];
  }
  ASSERT_GT(dark, 500);
  vsmLight /= dark;
  evsmLight /= dark;
  RecordProperty("vsm_mean_light_in_pcf_shadow", std::to_string(vsmLight));
  RecordProperty("evsm4_mean_light_in_pcf_shadow", std::to_string(evsmLight));
  EXPECT_GT(vsmLight, 0.02);
  EXPECT_LT(evsmLight, 0.25 * vsmLight);
}

// Texels of a size^2 texture, with its full mip chain down to 1x1 when `mips`: size^2 (1 + 1/4 +
// ... + 1/size^2) = (4 size^2 - 1) / 3 for a power of two.
uint64_t texelsOf(uint64_t size, bool mips) {
  return mips ? (4 * size * size - 1) / 3 : size * size;
}

// Bytes per texel by the storage each technique's defaults give (docs/techniques.md's table):
// ESM R32F, VSM RG32F, EVSM4 RGBA32F, MSM RGBA16 (unorm16 moments), CSM M = 16: 8 RGBA8 layers.
struct TechniqueBytes {
  Technique technique;
  uint64_t bytesPerTexel;
};
// PCF and the hard test: none, their lookup reads the light pass's depth (no channel texture).
constexpr TechniqueBytes kDefaultTexelBytes[] = {
    {Technique::Hard, 0},       {Technique::Pcf, 0},       {Technique::Esm, 4},
    {Technique::Vsm, 2 * 4},    {Technique::Evsm4, 4 * 4}, {Technique::Msm, 4 * 2},
    {Technique::Csm, 8 * 4 * 1}};

TEST_F(RendererTest, ReportedAndAllocatedMemoryEqualTexelsTimesTexelBytes) {
  const Scene scene = makeBuiltinScene("planar");
  for (const TechniqueBytes& k : kDefaultTexelBytes) {
    for (gl::FilterMode filter : {gl::FilterMode::Bilinear, gl::FilterMode::Trilinear}) {
      gl::RenderSettings s = small(k.technique);
      s.filter = filter;
      const gl::RenderResult r = renderer->render(scene, s);
      const uint64_t expected =
          texelsOf(256, filter == gl::FilterMode::Trilinear) * k.bytesPerTexel;
      EXPECT_EQ(r.memory.technique, expected)
          << techniqueId(k.technique) << " " << filterModeName(filter);
      EXPECT_EQ(renderer->measuredChannelTextureBytes(), expected)
          << techniqueId(k.technique) << " " << filterModeName(filter);
    }
  }
}

// PCF and the hard test filter after the test, over the light pass's depth: a timed frame runs no
// encode, blur or mips for them (their stages read exactly 0, a stage that ran and was timed
// reads its glFinish round trip at least) and holds no channel texture; VSM's frame, the same
// settings otherwise, times each of its stages.
TEST_F(RendererTest, PcfAndTheHardTestRunNoEncodeBlurOrMips) {
  const Scene scene = makeBuiltinScene("planar");
  for (Technique t : {Technique::Hard, Technique::Pcf, Technique::Vsm}) {
    gl::RenderSettings s = small(t);
    s.filter = gl::FilterMode::Trilinear;
    const gl::RenderResult r = renderer->render(scene, s);
    ASSERT_TRUE(r.wallTimes.has_value()) << techniqueId(t);
    if (t == Technique::Vsm) {
      EXPECT_GT(r.wallTimes->encode, 0.0);
      EXPECT_GT(r.wallTimes->prefilter, 0.0);
      EXPECT_GT(r.wallTimes->mipsOrSat, 0.0);
      EXPECT_GT(r.memory.technique, 0u);
      continue;
    }
    EXPECT_EQ(r.wallTimes->encode, 0.0) << techniqueId(t);
    EXPECT_EQ(r.wallTimes->prefilter, 0.0) << techniqueId(t);
    EXPECT_EQ(r.wallTimes->mipsOrSat, 0.0) << techniqueId(t);
    EXPECT_GT(r.wallTimes->camera, 0.0) << techniqueId(t);
    EXPECT_EQ(r.memory.technique, 0u) << techniqueId(t);
    EXPECT_EQ(renderer->measuredChannelTextureBytes(), 0u) << techniqueId(t);
  }
}

// Their one channel, read back (the viewer's channel view, readChannels), is each cascade's own
// light-pass depth, texel for texel.
TEST_F(RendererTest, TheHardTestsChannelIsEachCascadesLightDepth) {
  gl::RenderSettings s = small(Technique::Hard);
  s.shadowMapSize = 64;
  s.cascades.count = 3;
  renderer->render(makeBuiltinScene("street"), s);
  int differing = 0;
  for (int cascade = 0; cascade < 3; ++cascade) {
    const Image channel = renderer->readChannels(0, cascade);
    const Image depth = renderer->readDepthMap(cascade);
    ASSERT_EQ(channel.channels(), 1);
    ASSERT_EQ(channel.data().size(), depth.data().size());
    differing += int(!std::ranges::equal(channel.data(), depth.data()));
  }
  EXPECT_EQ(differing, 0);
  // The cascades' maps differ (else the cascade index would not be tested).
  EXPECT_FALSE(
      std::ranges::equal(renderer->readDepthMap(0).data(), renderer->readDepthMap(2).data()));
}

// ESM paper Fig. 1 at a 2048^2 shadow map, mip maps included "(a factor of 1.3)", §5: ESM 21 MB,
// VSM 42 MB, CSM 170 MB. Its MB are MiB (2048^2 x 4 bytes = 16 MiB, x 1.3 = 20.8 -> 21; in 10^6
// bytes it would be 22), rounded to whole MiB, CSM's to two digits (128 x 1.3 = 166.4 -> 170).
// An exact chain is 4/3, not 1.3, so ours exceed base x 1.3 by base / 30: each figure must
// match within base / 30 plus its rounding. Measured on the GL objects the renderer allocates.
TEST_F(RendererTest, ChannelTexturesAtTwoKilotexelsMatchTheEsmPapersMemoryFigures) {
  struct Figure {
    Technique technique;
    double paperMiB;
    double baseMiB;  // 2048^2 texels (4 Mi) x bytes per texel, no mips
    double rounding;
  };
  const Image depth(2048, 2048, 1, 0.5f);
  for (const Figure& f :
       {Figure{Technique::Esm, 21.0, 4.0 * 4, 0.5}, Figure{Technique::Vsm, 42.0, 4.0 * 8, 0.5},
        Figure{Technique::Csm, 170.0, 4.0 * 32, 5.0}}) {
    gl::RenderSettings s = small(f.technique);
    s.filter = gl::FilterMode::Trilinear;
    s.blur.radius = 0;  // memory does not depend on the blur; this keeps llvmpipe quick
    renderer->filterDepthMap(depth, s);
    const double mib = double(renderer->measuredChannelTextureBytes()) / (1024.0 * 1024.0);
    EXPECT_NEAR(mib, f.paperMiB, f.baseMiB / 30.0 + f.rounding) << techniqueId(f.technique);
    EXPECT_NEAR(mib / f.baseMiB, 1.3, 0.05)
        << "the paper's mip factor " << techniqueId(f.technique);
  }
}

void expectSameMemory(const gl::MemoryReport& estimated, const gl::MemoryReport& allocated,
                      const std::string& where) {
  EXPECT_EQ(estimated.lightPass, allocated.lightPass) << where;
  EXPECT_EQ(estimated.technique, allocated.technique) << where;
  EXPECT_EQ(estimated.summedArea, allocated.summedArea) << where;
  EXPECT_EQ(estimated.scratch, allocated.scratch) << where;
  EXPECT_EQ(estimated.auxiliary, allocated.auxiliary) << where;
  EXPECT_EQ(estimated.frame, allocated.frame) << where;
}

TEST_F(RendererTest, EstimatedMemoryEqualsWhatEveryRenderAllocates) {
  // The up-front estimate that validate() checks is exact, for every technique, filter, MSAA,
  // blur and auxiliary pass: against what the render reports and, for the channel texture,
  // against the GL object itself.
  const Scene scene = makeBuiltinScene("planar");
  std::vector<gl::RenderSettings> cases;
  for (Technique t : allTechniques()) {
    for (gl::FilterMode filter :
         {gl::FilterMode::Point, gl::FilterMode::Trilinear, gl::FilterMode::SummedArea}) {
      for (int msaa : {1, 4}) {
        gl::RenderSettings s = small(t);
        s.shadowMapSize = 64;
        s.width = 40;
        s.height = 24;
        s.filter = filter;
        s.msaaSamples = msaa;
        cases.push_back(s);
      }
    }
  }
  gl::RenderSettings s = small(Technique::Esm);
  s.params.esm.classifier = shaders::kEsmClassifyZmax;
  cases.push_back(s);
  s = small(Technique::Lvsm);
  s.params.lvsm.placement = shaders::kLayerPlacementUniform;
  cases.push_back(s);
  s = small(Technique::Vsm);
  s.blur.radius = 0;
  cases.push_back(s);
  s.lookupInputs = false;  // the colour alone (writesDiagnostics)
  s.readBack = gl::frame_image::kColor;
  cases.push_back(s);
  int rendered = 0;
  for (const gl::RenderSettings& c : cases) {
    const std::string where = std::string(techniqueId(c.technique)) + " " +
                              std::string(filterModeName(c.filter)) + " msaa " +
                              std::to_string(c.msaaSamples);
    try {
      renderer->validate(c);
    } catch (const Error&) {
      continue;  // e.g. the summed-area filter with exponential channels
    }
    const gl::MemoryReport estimated = gl::estimateMemory(c);
    expectSameMemory(estimated, renderer->render(scene, c).memory, where);
    // The report is computed by the same formulas as the estimate; the channel texture, the
    // largest allocation, and the camera pass's targets are also measured on the GL objects
    // the render left.
    EXPECT_EQ(renderer->measuredChannelTextureBytes(), estimated.technique) << where;
    EXPECT_EQ(renderer->measuredFrameBytes(), estimated.frame) << where;
    ++rendered;
  }
  EXPECT_GT(rendered, 50);
}

// The lookup's inputs are compiled out of the camera pass unless asked for
// (RenderSettings::lookupInputs): the picture, visibility and diagnostic must not change with
// them, the frame must hold four targets (48 bytes per pixel) fewer, as estimated, and what reads
// the inputs must refuse such a frame instead of reading nothing. The foliage scene draws
// alpha-tested and opaque meshes (both variants of the pass); ESM and LVSM write diagnostics.
TEST_F(RendererTest, AFrameWithoutTheLookupInputsDrawsTheSamePictureInFewerTargets) {
  const Scene scene = makeBuiltinScene("foliage");
  for (Technique t : {Technique::Vsm, Technique::Esm, Technique::Lvsm}) {
    const std::string where(techniqueId(t));
    gl::RenderSettings lean = small(t);
    lean.lookupInputs = false;
    const gl::RenderResult full = renderer->render(scene, small(t));
    const gl::RenderResult r = renderer->render(scene, lean);
    // The same arithmetic on the same inputs: only stores were removed, so the bits agree.
    EXPECT_TRUE(std::ranges::equal(r.color.data(), full.color.data())) << where;
    EXPECT_TRUE(std::ranges::equal(r.visibility.data(), full.visibility.data())) << where;
    EXPECT_TRUE(std::ranges::equal(r.diagnostic.data(), full.diagnostic.data())) << where;
    EXPECT_EQ(full.memory.frame - r.memory.frame, uint64_t(160 * 90 * 48)) << where;
    EXPECT_EQ(r.memory.frame, gl::estimateMemory(lean).frame) << where;
    EXPECT_EQ(r.lookup.channels(), 0) << where;
    EXPECT_THROW(litSurfaceMask(r.lookup), Error) << where;
    EXPECT_THROW(gl::lookupPixelAt(r, 0, 0), Error) << where;
  }
}

// A frame reads back only the images asked for (RenderSettings::readBack) and times its passes
// only when asked (RenderSettings::timing); neither changes what is drawn. ESM's failure rate is
// counted on the diagnostic where the frame reads it back, and is 0 elsewhere.
TEST_F(RendererTest, AFrameReadsBackOnlyTheImagesAskedForAndTimesOnlyWhenAsked) {
  namespace fi = gl::frame_image;
  const Scene scene = makeBuiltinScene("backyard");
  gl::RenderSettings s = small(Technique::Esm);
  s.params.esm.classifier = shaders::kEsmClassifyZmax;
  const gl::RenderResult full = renderer->render(scene, s);
  ASSERT_GT(full.failureRatePercent, 0.0) << "the view must show ESM's classifier failing";
  EXPECT_GT(full.wallTimes.value().total(), 0.0);
  // A software rasteriser reports no GPU times even for a timed frame (its queries see only
  // submission, so what they read is not a GPU time); where the queries measure execution a
  // timed frame has them, an untimed none.
  const bool gpuTimed = renderer->timerQueriesMeasureExecution();
  ASSERT_EQ(full.gpuTimes.has_value(), gpuTimed);
  if (gpuTimed) {
    EXPECT_GT(full.gpuTimes->total(), 0.0);
  }
  const std::pair<unsigned, const Image gl::RenderResult::*> images[] = {
      {fi::kColor, &gl::RenderResult::color},
      {fi::kVisibility, &gl::RenderResult::visibility},
      {fi::kDiagnostic, &gl::RenderResult::diagnostic},
      {fi::kLookup, &gl::RenderResult::lookup},
      {fi::kReceiverPlane, &gl::RenderResult::receiverPlane},
      {fi::kUvDerivatives, &gl::RenderResult::uvDerivatives},
      {fi::kCascades, &gl::RenderResult::cascades}};
  for (const auto& [bit, image] : images) {
    gl::RenderSettings one = s;
    one.readBack = bit;
    one.timing = false;
    const gl::RenderResult r = renderer->render(scene, one);
    for (const auto& [otherBit, other] : images) {
      EXPECT_EQ((r.*other).empty(), otherBit != bit)
          << "asked for " << bit << ", image " << otherBit;
    }
    EXPECT_TRUE(std::ranges::equal((r.*image).data(), (full.*image).data())) << bit;
    EXPECT_EQ(r.failureRatePercent, bit == fi::kDiagnostic ? full.failureRatePercent : 0.0) << bit;
    EXPECT_FALSE(r.wallTimes.has_value()) << "an untimed frame reported wall times";
    EXPECT_FALSE(r.gpuTimes.has_value()) << "an untimed frame reported GPU times";
  }
  // Timing on again: the passes are timed.
  const gl::RenderResult again = renderer->render(scene, s);
  EXPECT_GT(again.wallTimes.value().total(), 0.0);
  EXPECT_EQ(again.gpuTimes.has_value(), gpuTimed);
}

// A frame that reads neither the visibility nor the diagnostic, and writes no lookup inputs,
// compiles both targets out (writesDiagnostics): the same picture, two R32F targets (8 bytes per
// pixel) fewer, as estimated. ESM
// (its failure diagnostic) and LVSM (its layer index) write diagnostics of their own.
TEST_F(RendererTest, AFrameThatReadsNoDiagnosticsDrawsTheSameColourAlone) {
  namespace fi = gl::frame_image;
  const Scene scene = makeBuiltinScene("foliage");
  for (Technique t : {Technique::Vsm, Technique::Esm, Technique::Lvsm}) {
    const std::string where(techniqueId(t));
    gl::RenderSettings withDiagnostics = small(t);
    withDiagnostics.lookupInputs = false;
    withDiagnostics.readBack = fi::kColor | fi::kDiagnostic;
    gl::RenderSettings colourAlone = withDiagnostics;
    colourAlone.readBack = fi::kColor;
    const gl::RenderResult full = renderer->render(scene, withDiagnostics);
    const uint64_t fullTargets = renderer->measuredFrameBytes();
    const gl::RenderResult r = renderer->render(scene, colourAlone);
    // Only stores were removed: the bits agree.
    EXPECT_TRUE(std::ranges::equal(r.color.data(), full.color.data())) << where;
    // What the GL holds, measured on the targets, and what the report and the estimate say.
    EXPECT_EQ(fullTargets - renderer->measuredFrameBytes(), uint64_t(160 * 90 * 8)) << where;
    EXPECT_EQ(renderer->measuredFrameBytes(), gl::estimateMemory(colourAlone).frame) << where;
    EXPECT_EQ(r.memory.frame, gl::estimateMemory(colourAlone).frame) << where;
    EXPECT_EQ(full.memory.frame, gl::estimateMemory(withDiagnostics).frame) << where;
  }
}

TEST_F(RendererTest, SettingsBeyondTheMemoryBudgetAreRefusedWithTheLargestSizeThatFits) {
  gl::RenderSettings s = small(Technique::Evsm4);
  s.shadowMapSize = 1024;
  const uint64_t need = gl::estimateMemory(s).total();
  renderer->limitMemory(need);
  EXPECT_NO_THROW(renderer->validate(s));  // the budget is inclusive
  renderer->limitMemory(need / 2);
  std::string message;
  try {
    renderer->validate(s);
  } catch (const Error& e) {
    message = e.what();
  }
  renderer->limitMemory(0);
  // Counted down independently of validate()'s bisection.
  int largest = s.shadowMapSize;
  for (gl::RenderSettings smaller = s; gl::estimateMemory(smaller).total() > need / 2;) {
    smaller.shadowMapSize = --largest;
  }
  EXPECT_NE(message.find("evsm4 at shadow-map size 1024"), std::string::npos) << message;
  EXPECT_NE(message.find("(" + std::to_string(need) + " bytes)"), std::string::npos) << message;
  EXPECT_NE(message.find("more than the limit of"), std::string::npos) << message;
  const std::string advice = "the largest shadow-map size that fits is " + std::to_string(largest);
  EXPECT_EQ(message.substr(message.size() - std::min(message.size(), advice.size())), advice)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NO_THROW(renderer->validate(s));  // the cap is gone
}

TEST_F(RendererTest, TheUploadedScenesStorageCountsAgainstTheMemoryBudget) {
  // A scene too large for the device beside the render's textures is refused by validate() after
  // its upload and before any pass draws it (llvmpipe crashed drawing one within the textures'
  // budget). Here a 256^2 grid (130,050 triangles) under a cap set around it: cheap.
  constexpr int kSide = 256;
  Mesh mesh;
  for (int z = 0; z < kSide; ++z) {
    for (int x = 0; x < kSide; ++x) {
      mesh.vertices.push_back({glm::vec3(x, 0, z), glm::vec3(0, 1, 0), glm::vec2(0)});
      if (x + 1 == kSide || z + 1 == kSide) continue;
      const auto a = uint32_t(z * kSide + x), b = a + kSide;
      mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  Scene scene;
  scene.name = "grid";
  scene.meshes.push_back(mesh);
  // What the upload stores: one 32-byte vertex each, 32-bit indices, no texture.
  const uint64_t sceneBytes = 65536 * 32 + 390150 * 4;
  ASSERT_EQ(mesh.vertices.size(), 65536u);
  ASSERT_EQ(mesh.indices.size(), 390150u);
  ASSERT_EQ(sizeof(Vertex), 32u);
  const gl::RenderSettings s = small(Technique::Vsm);
  const uint64_t textures = gl::estimateMemory(s).total();
  const auto refusal = [&] {
    try {
      renderer->validate(s);
      return std::string("accepted");
    } catch (const Error& e) {
      return std::string(e.what());
    }
  };
  renderer->limitMemory(textures);
  EXPECT_EQ(refusal(), "accepted");  // no scene yet
  renderer->setScene(scene);
  const std::string message = refusal();
  EXPECT_NE(message.find("(" + std::to_string(textures + sceneBytes) + " bytes, the scene's " +
                         std::to_string(sceneBytes) + " included)"),
            std::string::npos)
      << message;
  renderer->limitMemory(textures + sceneBytes);
  EXPECT_EQ(refusal(), "accepted");  // the budget is inclusive
  renderer->limitMemory(sceneBytes);
  EXPECT_NE(refusal().find("the scene's geometry and textures alone take"), std::string::npos)
      << refusal();
  renderer->limitMemory(0);
}

// Checked on counts: a scene at the limit takes 2 GiB of host memory. (llvmpipe drew a
// 2,147,200,000-byte vertex buffer and crashed on a 2,240,000,000-byte one.)
TEST(SceneBuffers, SoftwareRasterizersRefuseABufferBeyondSignedThirtyTwoBitOffsets) {
  const std::string llvmpipe = "llvmpipe (LLVM 15.0.6, 256 bits)";
  // 2^26 vertices of 32 bytes and 2^29 indices of 4 are 2^31 bytes, one past the largest offset.
  constexpr uint64_t kVertices = uint64_t(1) << 26, kIndices = uint64_t(1) << 29;
  EXPECT_EQ(gl::sceneBufferShortfall(kVertices - 1, kIndices - 1, llvmpipe), "");
  EXPECT_EQ(gl::sceneBufferShortfall(kVertices, 3, llvmpipe),
            "its 67108864 vertices take 2147483648 bytes in one buffer (32 each), and " + llvmpipe +
                " draws from buffers of at most 2147483647 bytes (signed 32-bit offsets; it "
                "crashes beyond)");
  EXPECT_NE(gl::sceneBufferShortfall(3, kIndices, llvmpipe).find("its 536870912 indices take "),
            std::string::npos);
  EXPECT_EQ(gl::sceneBufferShortfall(kVertices * 4, kIndices * 4, "NVIDIA H200/PCIe/SSE2"), "")
      << "a GPU's driver takes larger buffers";
}

TEST_F(RendererTest, TexturesTheGlCannotCreateAreRefusedBeforeAllocation) {
  // The case: EVSM4 at 16384^2 is a 5.3 GiB texture, which llvmpipe cannot create (its
  // textures stay below 2 GiB); validate() asks the GL's proxy test instead of failing in
  // glTexStorage3D. Vendor GPUs may hold it, so the case is llvmpipe's.
  if (renderer->deviceDescription().find("llvmpipe") == std::string::npos) {
    GTEST_SKIP() << "per-texture limits differ on " << renderer->deviceDescription();
  }
  gl::RenderSettings s = small(Technique::Evsm4);
  s.shadowMapSize = 16384;
  std::string message;
  try {
    renderer->validate(s);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("cannot create its 16384x16384 channel texture"), std::string::npos)
      << message;
  const size_t at = message.find("the largest shadow-map size that fits is ");
  ASSERT_NE(at, std::string::npos) << message;
  const int largest = std::stoi(message.substr(at + 41));
  s.shadowMapSize = largest;
  EXPECT_NO_THROW(renderer->validate(s));
  s.shadowMapSize = largest + 1;
  EXPECT_THROW(renderer->validate(s), Error);
}

TEST_F(RendererTest, GaussianPcfIsTheFilteredReferenceForEveryBlurRadius) {
  // With point lookups the reference is PCF under the blur's kernel (docs/reference.md), for
  // every radius the blur takes (up to 64) and sigmas at both ends of its range. Radius 16 and
  // above once broke on llvmpipe: per-tap kernel normalisation ran past its 65535-iteration loop
  // limit. The tolerance is fp32 summation: the reference's weights come from the CPU.
  const Scene scene = makeBuiltinScene("planar");
  for (int radius : {15, 16, 64}) {
    for (float sigma : {0.01f, 0.5f, 20.0f, 64.0f}) {
      gl::RenderSettings s = small(Technique::Pcf);
      s.shadowMapSize = 128;
      s.width = 64;
      s.height = 36;
      s.filter = gl::FilterMode::Point;
      s.blur = {BlurKernel::Gaussian, radius, sigma};
      s.params.pcf.kernel = shaders::kKernelGaussian;
      s.params.pcf.radius = radius;
      s.params.pcf.sigma = sigma;
      s.params.pcf.bias.constantBias = shaders::kReferenceTie;
      s.params.pcf.bias.slopeScaledBias = 0.0f;
      const Image pcf = renderer->render(scene, s).visibility;
      const Image reference = renderer->renderReference(scene, s, 1).visibility;
      float worst = 0.0f;
      for (size_t i = 0; i < pcf.data().size(); ++i) {
        worst = std::max(worst, std::abs(pcf.data()[i] - reference.data()[i]));
      }
      EXPECT_LT(worst, 1e-5f) << "radius " << radius << " sigma " << sigma;
    }
  }
}

TEST_F(RendererTest, MsaaEncodeOfEveryTechniqueReducesItsEncodedSamplesLikeTheCpu) {
  // Each light-pass sample encoded, then the samples reduced like filter taps of equal weight:
  // means for moments and basis terms, the power CDF's min and max, ESM's log-mean-exp under
  // log filtering (encode.comp); for PCF, which has no encode, the nearest sample its lookup reads
  // (lightDepthTexel, through readChannels' passes/light_depth_texels.comp). Against the CPU doing
  // that to the samples the GPU rendered, rounded to storage: the tolerance is the prefilter
  // parity's (two storage roundings, or 2e-5 relative in fp32 for the GPU's own rounding of
  // exponentials and of CSM's walk). Each case must also tell this from encoding the samples' mean
  // depth, which silhouette texels (samples differ) would give away on a few hundred texels.
  const Scene scene = makeBuiltinScene("backyard");
  struct Case {
    Technique technique;
    const char* param;  // NAME=VALUE applied on top of the defaults, or nullptr
  };
  for (const Case& k : {Case{Technique::Pcf, nullptr}, Case{Technique::Vsm, nullptr},
                        Case{Technique::Lvsm, "placement=uniform"}, Case{Technique::Evsm4, nullptr},
                        Case{Technique::Esm, nullptr}, Case{Technique::Esm, "filtering=log"},
                        Case{Technique::Csm, nullptr}, Case{Technique::Csm, "storage=float32"},
                        Case{Technique::PowerCdf, nullptr}, Case{Technique::Msm, nullptr}}) {
    gl::RenderSettings s = small(k.technique);
    // Not a multiple of the 16 or 32 rows an encode group covers (encodeRowsPerInvocation): the
    // last groups' rows past the edge fetch the last row and store nothing.
    s.shadowMapSize = 120;
    s.blur.radius = 0;
    s.filter = gl::FilterMode::Point;
    s.msaaSamples = 4;
    if (k.param != nullptr) {
      const std::vector<Technique> one{k.technique};
      applyParamAssignment(one, s.params, k.param);
    }
    renderer->render(scene, s);
    const Image samples = renderer->readDepthSamples();
    const Image gpu = renderer->readChannels(0);
    const int count = channelCount(k.technique, s.params);
    ASSERT_EQ(samples.channels(), 4);
    ASSERT_EQ(gpu.channels(), count);
    const StorageFormat storage = techniqueStorage(k.technique, s.params);
    const bool nearestSample = k.technique == Technique::Pcf || k.technique == Technique::Hard;
    int silhouettes = 0, bad = 0, meanDepthWouldFail = 0;
    std::vector<float> encoded(static_cast<size_t>(count), 0.0f),
        ofMean(static_cast<size_t>(count), 0.0f);
    for (int y = 0; y < samples.height(); ++y) {
      for (int x = 0; x < samples.width(); ++x) {
        std::vector<shaders::ChannelAccumulator> acc;
        for (int c = 0; c < count; ++c) {
          const int reduction =
              nearestSample ? shaders::kReduceMin : int(channelReduction(k.technique, s.params, c));
          acc.push_back(shaders::startReduction(reduction, s.params.esm.exponent));
        }
        float lo = 1.0f, hi = 0.0f, mean = 0.0f;
        for (int sample = 0; sample < 4; ++sample) {
          const float depth = samples.at(x, y, sample);
          lo = std::min(lo, depth);
          hi = std::max(hi, depth);
          mean += 0.25f * depth;
          encodeDepth(k.technique, s.params, depth, encoded);
          for (int c = 0; c < count; ++c) {
            acc[size_t(c)] = shaders::accumulateTap(acc[size_t(c)], encoded[size_t(c)], 0.25f);
          }
        }
        silhouettes += hi - lo > 1e-3f;
        encodeDepth(k.technique, s.params, mean, ofMean);
        for (int c = 0; c < count; ++c) {
          const float expected =
              quantizeToStorage(shaders::reductionResult(acc[size_t(c)]), storage);
          const float got = gpu.at(x, y, c);
          const float wrong = quantizeToStorage(ofMean[size_t(c)], storage);
          meanDepthWouldFail += !(std::abs(wrong - expected) <= tolerance(storage, expected));
          if (!(std::abs(got - expected) <= tolerance(storage, expected)) && ++bad <= 3) {
            ADD_FAILURE() << techniqueId(k.technique) << (k.param ? k.param : "") << " texel " << x
                          << "," << y << " channel " << c << ": gpu " << got << " cpu " << expected;
          }
        }
      }
    }
    EXPECT_EQ(bad, 0) << techniqueId(k.technique) << (k.param ? k.param : "");
    EXPECT_GT(silhouettes, 200) << techniqueId(k.technique);
    EXPECT_GT(meanDepthWouldFail, 100) << techniqueId(k.technique) << (k.param ? k.param : "");
  }
}

TEST_F(RendererTest, DocumentedBoundsOfFloatSettingsAreAcceptedAndOneStepBeyondIsNot) {
  // Settings hold floats; --blur-sigma 0.01 arrives as 0.00999999978f.
  auto check = [&](auto set, float lo, float hi, const char* what) {
    for (float v : {lo, hi}) {
      gl::RenderSettings s = small(Technique::Vsm);
      set(s, v);
      EXPECT_NO_THROW(renderer->validate(s)) << what << " " << v;
    }
    for (float v : {std::nextafter(lo, -INFINITY), std::nextafter(hi, INFINITY)}) {
      gl::RenderSettings s = small(Technique::Vsm);
      set(s, v);
      EXPECT_THROW(renderer->validate(s), Error) << what << " " << v;
    }
  };
  check([](gl::RenderSettings& s, float v) { s.blur.sigma = v; }, 0.01f, 64.0f, "blur sigma");
  check([](gl::RenderSettings& s, float v) { s.normalOffsetTexels = v; }, 0.0f, 10.0f,
        "normal offset");
  check([](gl::RenderSettings& s, float v) { s.ambient = v; }, 0.0f, 1.0f, "ambient");
}

TEST_F(RendererTest, BadSettingsAreRejectedWithTheRange) {
  gl::RenderSettings s = small(Technique::Vsm);
  s.shadowMapSize = 0;
  EXPECT_THROW(renderer->validate(s), Error);
  s = small(Technique::Vsm);
  s.msaaSamples = 3;
  EXPECT_THROW(renderer->validate(s), Error);
  s = small(Technique::PowerCdf);
  s.filter = gl::FilterMode::SummedArea;
  EXPECT_THROW(renderer->validate(s), Error);
  s = small(Technique::Evsm4);  // exponential moments overflow any fixed-point range
  s.filter = gl::FilterMode::SummedArea;
  EXPECT_THROW(renderer->validate(s), Error);
  s = small(Technique::Vsm);
  s.width = 1 << 20;
  EXPECT_THROW(renderer->validate(s), Error);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

class ReferenceTest : public testing::GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (context) renderer = std::make_unique<gl::Renderer>(*context);
  }
  std::unique_ptr<gl::Renderer> renderer;
};

// Brute force on the CPU, straight from the definition in docs/reference.md: blur (box) at level
// 0, bilinear taps, every test against the receiver plane extended to the tested texel.
float bruteForceReference(const Image& depth, float u, float v, float receiver, float gx, float gy,
                          const std::vector<float>& blur) {
  const int size = depth.width();
  const int r = int(blur.size() / 2);
  const double px = double(u) * size, py = double(v) * size;
  const double bx = std::floor(px - 0.5), by = std::floor(py - 0.5);
  const double fx = px - 0.5 - bx, fy = py - 0.5 - by;
  double lit = 0.0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const double w = (i == 0 ? 1 - fx : fx) * (j == 0 ? 1 - fy : fy);
      const int tx = std::clamp(int(bx) + i, 0, size - 1),
                ty = std::clamp(int(by) + j, 0, size - 1);
      for (int b = -r; b <= r; ++b) {
        for (int a = -r; a <= r; ++a) {
          const float z = depth.clamped(tx + a, ty + b);
          const double d = receiver + gx * (tx + a + 0.5 - px) + gy * (ty + b + 0.5 - py);
          lit += w * blur[size_t(a + r)] * blur[size_t(b + r)] *
                 (z >= d - shaders::kReferenceTie ? 1.0 : 0.0);
        }
      }
    }
  }
  return float(lit);
}

TEST_F(ReferenceTest, FilteredReferenceEqualsABruteForceCpuEvaluation) {
  gl::RenderSettings s;
  s.technique = Technique::Vsm;
  s.shadowMapSize = 256;
  s.width = 160;
  s.height = 90;
  s.blur = {BlurKernel::Box, 2, 1.0f};
  s.filter = gl::FilterMode::Bilinear;
  const gl::RenderResult r = renderer->renderReference(makeBuiltinScene("contact"), s, 1);
  const Image depth = renderer->readDepthMap();
  const std::vector<float> blur = blurWeights(s.blur);
  int checked = 0, bad = 0, partial = 0;
  for (int y = 0; y < r.lookup.height(); ++y) {
    for (int x = 0; x < r.lookup.width(); ++x) {
      if (r.lookup.at(x, y, 3) < 0.5f) continue;
      const float cpu = bruteForceReference(depth, r.lookup.at(x, y, 0), r.lookup.at(x, y, 1),
                                            r.lookup.at(x, y, 2), r.receiverPlane.at(x, y, 0),
                                            r.receiverPlane.at(x, y, 1), blur);
      ++checked;
      partial += cpu > 0.01f && cpu < 0.99f;
      if (std::abs(cpu - r.visibility.at(x, y)) > 1e-4f && ++bad <= 5) {
        ADD_FAILURE() << "pixel " << x << "," << y << ": gpu " << r.visibility.at(x, y) << " cpu "
                      << cpu;
      }
    }
  }
  EXPECT_GT(checked, 5000);
  EXPECT_GT(partial, 100);
  EXPECT_LE(bad, checked / 1000) << "ties at a tested texel may round either way";
}

// docs/reference.md: the ground truth is the filtered reference at S x S sub-pixel positions,
// box-averaged; here S = 4 against a reference rendered at 4x the size and averaged in double.
// The renderer sums 16 fp32 values in [0,1]: at most 16 x 2^-24 = 1e-6 apart.
TEST_F(ReferenceTest, SupersampledGroundTruthIsTheBoxAverageOfTheReferenceAtFourTimesTheSize) {
  constexpr int kFactor = 4;
  gl::RenderSettings s;
  s.shadowMapSize = 256;
  s.width = 80;
  s.height = 45;
  s.filter = gl::FilterMode::Trilinear;
  const Scene scene = makeBuiltinScene("minification");
  const Image truth = renderer->renderReference(scene, s, kFactor).visibility;
  gl::RenderSettings big = s;
  big.width = s.width * kFactor;
  big.height = s.height * kFactor;
  const gl::RenderResult fineLookups = renderer->renderReference(scene, big, 1);
  const Image& fine = fineLookups.visibility;
  ASSERT_EQ(truth.width(), s.width);
  ASSERT_EQ(truth.height(), s.height);
  int bad = 0, mixed = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      double sum = 0.0;
      float lowest = 1.0f, highest = 0.0f;
      for (int j = 0; j < kFactor; ++j) {
        for (int i = 0; i < kFactor; ++i) {
          const float v = fine.at(x * kFactor + i, y * kFactor + j);
          sum += v;
          lowest = std::min(lowest, v);
          highest = std::max(highest, v);
        }
      }
      const double expected = sum / (kFactor * kFactor);
      mixed += highest - lowest > 0.5f;
      if (std::abs(truth.at(x, y) - expected) > 2e-6 && ++bad <= 3) {
        ADD_FAILURE() << "pixel " << x << "," << y << ": ground truth " << truth.at(x, y)
                      << ", mean of its sub-pixels " << expected;
      }
    }
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(mixed, 20) << "the check must cover pixels whose sub-pixels see the posts differently";

  // The average above is over the fine render's pixels; that they are the S x S sub-pixel
  // positions of each pixel is checked on the geometry. Where a pixel's 16 sub-pixels lie on one
  // plane (their uv an affine grid: every second difference under 1/16 of a grid step), the
  // grid's centroid must be the uv the pixel's own centre looks up. A shift by half a sub-pixel
  // moves it by half a step; perspective over one pixel bends it far less than the 1/16 step
  // allowed, fp32 uv rounding (6e-8) less still. Surfaces the light sees edge-on (a sub-pixel
  // step beyond a shadow-map texel) are left out: there uv is ill-conditioned in the screen
  // position (3 of 900 such pixels sit half a step off).
  const float texel = 1.0f / float(s.shadowMapSize);
  const gl::RenderResult coarse = renderer->renderReference(scene, s, 1);
  int planar = 0, misplaced = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      if (coarse.lookup.at(x, y, 3) < 1.0f) continue;
      glm::vec2 grid[kFactor][kFactor];
      bool valid = true;
      for (int j = 0; j < kFactor; ++j) {
        for (int i = 0; i < kFactor; ++i) {
          valid &= fineLookups.lookup.at(x * kFactor + i, y * kFactor + j, 3) >= 1.0f;
          grid[j][i] = gl::lookupPixelAt(fineLookups, x * kFactor + i, y * kFactor + j).uv;
        }
      }
      if (!valid) continue;
      const float step =
          std::max(glm::length(grid[0][1] - grid[0][0]), glm::length(grid[1][0] - grid[0][0]));
      float bend = 0.0f;
      glm::vec2 centroid(0.0f);
      for (int j = 0; j < kFactor; ++j) {
        for (int i = 0; i < kFactor; ++i) {
          centroid += grid[j][i] / float(kFactor * kFactor);
          if (i > 0 && i + 1 < kFactor) {
            bend = std::max(bend, glm::length(grid[j][i + 1] - 2.0f * grid[j][i] + grid[j][i - 1]));
          }
          if (j > 0 && j + 1 < kFactor) {
            bend = std::max(bend, glm::length(grid[j + 1][i] - 2.0f * grid[j][i] + grid[j - 1][i]));
          }
        }
      }
      if (!(step > 0.0f) || step > texel || bend > step / 16.0f) continue;
      ++planar;
      const float offset = glm::length(centroid - gl::lookupPixelAt(coarse, x, y).uv);
      if (offset > step / 16.0f + 1e-6f && ++misplaced <= 3) {
        ADD_FAILURE() << "pixel " << x << "," << y << ": its sub-pixels' centroid lies "
                      << offset / step << " sub-pixel steps from its centre";
      }
    }
  }
  EXPECT_EQ(misplaced, 0) << "of " << planar;
  EXPECT_GT(planar, s.width * s.height / 5);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST_F(RendererTest, SummedAreaTablesBeyondOneStorageBufferAreRefusedUpFront) {
  // CSM's 32 channels at 4096^2 need 4 GiB of 64-bit sums in one buffer, 32 x 4096 rows of
  // 4096 + 8 sums (each row padded by one 64-byte line, shared/summed_area.h): beyond any GL's
  // storage-block limit and, at 8192^2 with 16 LVSM layers, beyond 32-bit indexing.
  gl::RenderSettings s = small(Technique::Csm);
  s.filter = gl::FilterMode::SummedArea;
  s.shadowMapSize = 4096;
  try {
    renderer->validate(s);
    FAIL() << "a 4 GiB summed-area table must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needs 4303355904 bytes in one storage buffer"),
              std::string::npos)
        << e.what();
  }
  s.shadowMapSize = 256;  // 16 MiB: fine
  EXPECT_NO_THROW(renderer->validate(s));
}

}  // namespace
}  // namespace penumbra
