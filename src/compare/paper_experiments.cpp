// The papers' performance experiments as penumbra cases: which techniques, parameters and
// kernels each table or figure compared, and the paper's own ratios beside them
// (docs/results/papers-perf-numbers.md quotes where each figure comes from).
#include <algorithm>
#include <array>

#include "penumbra/compare/paper_bench.h"
#include "penumbra/error.h"
#include "penumbra/params.h"

namespace penumbra::compare {
namespace {

// A case's settings: the experiment's map and frame sizes, a k x k box prefilter (k odd) and
// bilinear lookups (no mips: the prefilter is the filter, as in the papers' tables).
gl::RenderSettings caseSettings(Technique technique, int shadowMapSize, const BenchSizes& z,
                                int kernel, std::initializer_list<const char*> params = {}) {
  gl::RenderSettings s;
  s.technique = technique;
  s.params = defaultTechniqueParams();
  for (const char* p : params) {
    const std::array<Technique, 1> one{technique};
    applyParamAssignment(one, s.params, p);
  }
  s.shadowMapSize = shadowMapSize;
  s.width = z.width;
  s.height = z.height;
  s.blur = {BlurKernel::Box, (kernel - 1) / 2, 1.0f};
  s.filter = FilterMode::Bilinear;
  return s;
}

std::string kernelName(int k) {
  return std::to_string(k) + "x" + std::to_string(k);
}

Experiment esmTable1(const BenchSizes& z) {
  Experiment e;
  e.id = "esm-table1";
  e.title = "ESM paper, Table 1 and Fig. 1: ESM, VSM and convolution shadow maps";
  e.claim =
      "ESM filters one channel where VSM needs two and convolution shadow maps M = 16 need "
      "thirty-two 8-bit ones: at 2048² with a 7x7 Gauss filter CSM runs at 19 fps against "
      "ESM's 86 (4.5x its frame time), and needs 8x its memory (Fig. 1: 170 MB against 21 MB).";
  e.xLabel = "Gauss filter width k (k x k; 1: none)";
  e.baselineSeries = "ESM (threshold)";
  // Frame-time ratios against ESM with thresholding from the paper's frame rates at 2048²
  // (Table 1 for no filter, 3x3 and 7x7; Fig. 1 for 5x5, which gives no Z-max figure).
  struct PaperFps {
    int kernel;
    double threshold, zmax, vsm, csm;  // fps; zmax < 0: not given
  };
  const PaperFps paper[] = {
      {1, 119, 101, 106, 40}, {3, 102, 78, 87, 27}, {5, 94, -1, 84, 22}, {7, 86, 61, 78, 19}};
  for (const PaperFps& row : paper) {
    const int k = row.kernel;
    const std::string source =
        k == 5 ? "ESM paper Fig. 1 (2k x 2k, 5x5 Gauss)" : "ESM paper Table 1 (S = 2048²)";
    auto add = [&](const std::string& series, Technique t, std::initializer_list<const char*> p,
                   double fps, double paperMemory) {
      BenchCase c;
      c.series = series;
      c.label = series + ", " + (k == 1 ? std::string("no filter") : kernelName(k));
      c.x = k;
      c.settings = caseSettings(t, z.shadowMapSize, z, k, p);
      c.settings.blur = paperGaussFilter(k);
      c.settings.filter = FilterMode::Trilinear;  // the paper's figures include mip-maps
      if (fps > 0.0) {
        c.paperTimeRatio = row.threshold / fps;  // frame time is 1 / fps
        c.paperNote = source;
      }
      if (k == 5 && paperMemory > 0.0) c.paperMemoryRatio = paperMemory;
      e.cases.push_back(c);
    };
    // The paper's fallback for failing pixels: its 2x2 custom PCF on the ESM texels (§3.3).
    add("ESM (threshold)", Technique::Esm, {"classifier=threshold", "fallback=paper"},
        row.threshold, 1.0);
    add("ESM (Z-max)", Technique::Esm, {"classifier=zmax", "fallback=paper"}, row.zmax, -1.0);
    add("VSM", Technique::Vsm, {}, row.vsm, 42.0 / 21.0);
    add("CSM M=16", Technique::Csm, {"M=16"}, row.csm, 170.0 / 21.0);
  }
  return e;
}

Experiment csmTable1(const BenchSizes& z) {
  Experiment e;
  e.id = "csm-table1";
  e.title = "CSM paper, Table 1: convolution shadow maps M = 4, 8, 16 against PCF";
  e.claim =
      "Against the hardware 2x2 PCF, convolution shadow maps with 16x anisotropic trilinear "
      "filtering cost more as M grows (M/2 RGBA fetches per pixel) and as the extra "
      "convolution widens: at 2048², 1.4x PCF's frame time for M = 4 without convolution up to "
      "4.9x for M = 16 with 7x7.";
  e.xLabel = "extra convolution width C (C x C; 1: none)";
  e.baselineSeries = "PCF";
  // The paper's frame rates at S = 2048² (Table 1): PCF 69 fps; CSM by M and C.
  const double pcfFps = 69.0;
  BenchCase pcf;
  pcf.series = "PCF";
  pcf.label = "PCF, 2x2 bilinear (the hardware shadow test)";
  pcf.settings = caseSettings(Technique::Pcf, z.shadowMapSize, z, 1);
  pcf.paperTimeRatio = 1.0;
  pcf.paperNote = "CSM paper Table 1 (S = 2048², 1024x768)";
  e.cases.push_back(pcf);
  struct PaperFps {
    int m;
    double none, c3, c7;
  };
  for (const PaperFps& row :
       {PaperFps{4, 50, 43, 36}, PaperFps{8, 38, 30, 24}, PaperFps{16, 26, 19, 14}}) {
    for (int k : {1, 3, 7}) {
      BenchCase c;
      c.series = "CSM M=" + std::to_string(row.m);
      c.label = c.series + ", " + (k == 1 ? std::string("no convolution") : kernelName(k));
      c.x = k;
      const std::string m = "M=" + std::to_string(row.m);
      c.settings = caseSettings(Technique::Csm, z.shadowMapSize, z, k, {m.c_str()});
      c.settings.blur = paperGaussFilter(k);
      c.settings.filter = FilterMode::AnisotropicDriver;  // the paper's hardware 16x anisotropic
      c.settings.anisotropy = 16;
      const double fps = k == 1 ? row.none : (k == 3 ? row.c3 : row.c7);
      c.paperTimeRatio = pcfFps / fps;
      c.paperNote = pcf.paperNote;
      e.cases.push_back(c);
    }
  }
  return e;
}

Experiment gumbauTable1(const BenchSizes& z) {
  Experiment e;
  e.id = "gumbau-table1";
  e.title = "Gumbau et al., Table 1: the power-function CDF against VSM and ESM";
  e.claim =
      "The power-function CDF stores three channels (min, max, mean); in 32 bits it costs 1.7x "
      "VSM's frame time at 2048², in 16 bits it is as fast as VSM and ESM (Table 1, 1920x1080: "
      "VSM 142 fps, ESM 165, CDF 32-bit 82, 16-bit 160).";
  e.baselineSeries = "VSM";
  const int k = 5;
  const double vsmFps = 142.0;
  auto add = [&](const std::string& series, Technique t, std::initializer_list<const char*> p,
                 double fps) {
    BenchCase c;
    c.series = series;
    c.label = series;
    c.settings = caseSettings(t, z.shadowMapSize, z, k, p);
    c.paperTimeRatio = vsmFps / fps;
    c.paperNote = "Gumbau et al. Table 1 (2048², 1920x1080; filter size not stated)";
    e.cases.push_back(c);
  };
  add("VSM", Technique::Vsm, {}, 142.0);
  add("ESM", Technique::Esm, {"classifier=none"}, 165.0);  // Gumbau's plain exponential test
  add("power CDF, 32-bit", Technique::PowerCdf, {"storage=float32"}, 82.0);
  add("power CDF, 16-bit", Technique::PowerCdf, {"storage=float16"}, 160.0);
  return e;
}

Experiment lvsmLayers(const BenchSizes& z) {
  Experiment e;
  e.id = "lvsm-layers";
  e.title = "Thesis Fig. 4.6: layered VSM cost against the number of layers";
  e.claim =
      "Each layer adds a two-channel map to encode, filter and read, yet LVSM stays real-time: "
      "with 14 layers at 1024² performance dips to just under 100 fps (1920x1200, 4x MSAA; "
      "Lloyd relaxation, trilinear and 16x anisotropic filtering, 16-bit storage). The figure's "
      "per-layer times are not in the text. Ours: no MSAA, at the bench's frame size.";
  e.xLabel = "layers";
  e.baselineSeries = "VSM";
  const int k = 5;
  const int size = std::min(1024, z.shadowMapSize);  // the thesis's 1024² map
  auto thesisSettings = [&](Technique t, std::initializer_list<const char*> p) {
    gl::RenderSettings s = caseSettings(t, size, z, k, p);
    s.filter = FilterMode::AnisotropicDriver;  // the thesis's hardware anisotropic filter
    s.anisotropy = 16;
    return s;
  };
  BenchCase vsm;
  vsm.series = "VSM";
  vsm.label = "VSM";
  vsm.settings = thesisSettings(Technique::Vsm, {});
  e.cases.push_back(vsm);
  for (int layers : {1, 2, 4, 8, 14}) {
    BenchCase c;
    c.series = "LVSM";
    c.label = "LVSM, " + std::to_string(layers) + (layers == 1 ? " layer" : " layers");
    c.x = layers;
    const std::string p = "layers=" + std::to_string(layers);
    c.settings = thesisSettings(Technique::Lvsm, {p.c_str(), "placement=lloyd"});
    e.cases.push_back(c);
  }
  return e;
}

Experiment kernelScaling(const BenchSizes& z) {
  Experiment e;
  e.id = "kernel-scaling";
  e.title = "Kernel scaling: PCF (k² taps), separable blur (2k taps), summed-area table (4 reads)";
  e.claim =
      "PCF's lookup grows with the kernel's area, a separable prefilter with its width, and a "
      "summed-area table not at all (thesis ch. 2-3; summed-area VSM, GPU Gems 3 ch. 8).";
  e.xLabel = "kernel width k (k x k)";
  e.baselineSeries = "PCF";
  e.fitsExponents = true;
  for (int k : {1, 3, 5, 7, 11, 15, 21, 31}) {
    auto add = [&](const std::string& series, Technique t, FilterMode filter) {
      BenchCase c;
      c.series = series;
      c.label = series + ", " + kernelName(k);
      c.x = k;
      c.settings = caseSettings(t, z.scalingShadowMapSize, z, k);
      c.settings.filter = filter;
      e.cases.push_back(c);
    };
    add("PCF", Technique::Pcf, FilterMode::Point);
    // The claim is about separate passes (2k taps per texel); the fused tile's cost grows with
    // its border's loads too ((16 + k - 1)^2 per 256 texels), so it is its own series, over the
    // kernels it takes.
    add("VSM, separable blur", Technique::Vsm, FilterMode::Bilinear);
    e.cases.back().settings.fusePrefilter = false;
    gl::RenderSettings fused = e.cases.back().settings;
    fused.fusePrefilter = true;
    if (k == 1 || gl::fusesPrefilter(fused, fused.blur.radius)) {
      add("VSM, fused blur", Technique::Vsm, FilterMode::Bilinear);
      e.cases.back().settings.fusePrefilter = true;
    }
    add("VSM, summed-area table", Technique::Vsm, FilterMode::SummedArea);
  }
  return e;
}

}  // namespace

BlurSpec paperGaussFilter(int k) {
  return {BlurKernel::Gaussian, (k - 1) / 2, std::max(0.5f, 0.25f * float(k - 1))};
}

std::vector<std::string> paperExperimentIds() {
  return {"esm-table1", "csm-table1", "gumbau-table1", "lvsm-layers", "kernel-scaling"};
}

Experiment makePaperExperiment(const std::string& id, const BenchSizes& sizes) {
  if (id == "esm-table1") return esmTable1(sizes);
  if (id == "csm-table1") return csmTable1(sizes);
  if (id == "gumbau-table1") return gumbauTable1(sizes);
  if (id == "lvsm-layers") return lvsmLayers(sizes);
  if (id == "kernel-scaling") return kernelScaling(sizes);
  std::string valid;
  for (const std::string& v : paperExperimentIds()) valid += (valid.empty() ? "" : ", ") + v;
  throw Error("unknown experiment '" + id + "'; valid experiments: " + valid);
}

}  // namespace penumbra::compare
