// The papers' performance experiments as penumbra cases: which techniques, parameters and
// kernels each table or figure compared, and the paper's own ratios beside them
// (docs/results/papers-perf-numbers.md quotes where each figure comes from).
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
      "sixteen: CSM costs several times ESM's time and 8x its memory.";
  e.baselineSeries = "ESM (threshold)";
  for (int k : {7, 5}) {
    auto add = [&](const std::string& series, Technique t, std::initializer_list<const char*> p) {
      BenchCase c;
      c.series = series;
      c.label = series + ", " + kernelName(k);
      c.x = k;
      c.settings = caseSettings(t, z.shadowMapSize, z, k, p);
      e.cases.push_back(c);
    };
    add("ESM (threshold)", Technique::Esm, {"classifier=threshold"});
    add("ESM (Z-max)", Technique::Esm, {"classifier=zmax"});
    add("VSM", Technique::Vsm, {});
    add("CSM M=16", Technique::Csm, {"M=16"});
  }
  return e;
}

Experiment csmTable1(const BenchSizes& z) {
  Experiment e;
  e.id = "csm-table1";
  e.title = "CSM paper, Table 1: convolution shadow maps M = 4, 8, 16 against PCF by kernel";
  e.claim =
      "Convolution shadow maps pay a fixed prefilter per frame, so their cost hardly grows with "
      "the kernel while PCF's grows with its area.";
  e.xLabel = "kernel width k (k x k taps)";
  e.baselineSeries = "PCF";
  for (int k : {3, 5, 7, 9, 11}) {
    auto add = [&](const std::string& series, Technique t, std::initializer_list<const char*> p) {
      BenchCase c;
      c.series = series;
      c.label = series + ", " + kernelName(k);
      c.x = k;
      c.settings = caseSettings(t, z.shadowMapSize, z, k, p);
      if (t == Technique::Pcf) c.settings.filter = FilterMode::Point;  // k x k taps exactly
      e.cases.push_back(c);
    };
    add("PCF", Technique::Pcf, {});
    add("CSM M=4", Technique::Csm, {"M=4"});
    add("CSM M=8", Technique::Csm, {"M=8"});
    add("CSM M=16", Technique::Csm, {"M=16"});
  }
  return e;
}

Experiment gumbauTable1(const BenchSizes& z) {
  Experiment e;
  e.id = "gumbau-table1";
  e.title = "Gumbau et al. 2010, Table 1: the power-function CDF against VSM and ESM";
  e.claim =
      "The power-function CDF stores three channels (min, max, mean), 16 bits enough: a cost "
      "close to VSM's.";
  e.baselineSeries = "VSM";
  const int k = 5;
  auto add = [&](const std::string& series, Technique t, std::initializer_list<const char*> p) {
    BenchCase c;
    c.series = series;
    c.label = series;
    c.settings = caseSettings(t, z.shadowMapSize, z, k, p);
    e.cases.push_back(c);
  };
  add("VSM", Technique::Vsm, {});
  add("ESM", Technique::Esm, {});
  add("power CDF, 32-bit", Technique::PowerCdf, {"storage=float32"});
  add("power CDF, 16-bit", Technique::PowerCdf, {"storage=float16"});
  return e;
}

Experiment lvsmLayers(const BenchSizes& z) {
  Experiment e;
  e.id = "lvsm-layers";
  e.title = "Thesis Fig. 4.6: layered VSM cost against the number of layers";
  e.claim = "Each layer adds a two-channel map to encode, blur and read: cost grows with layers.";
  e.xLabel = "layers";
  e.baselineSeries = "VSM";
  const int k = 5;
  BenchCase vsm;
  vsm.series = "VSM";
  vsm.label = "VSM";
  vsm.settings = caseSettings(Technique::Vsm, z.shadowMapSize, z, k);
  e.cases.push_back(vsm);
  for (int layers : {1, 2, 4, 6, 8}) {
    BenchCase c;
    c.series = "LVSM";
    c.label = "LVSM, " + std::to_string(layers) + (layers == 1 ? " layer" : " layers");
    c.x = layers;
    const std::string p = "layers=" + std::to_string(layers);
    c.settings = caseSettings(Technique::Lvsm, z.shadowMapSize, z, k, {p.c_str()});
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
    add("VSM, separable blur", Technique::Vsm, FilterMode::Bilinear);
    add("VSM, summed-area table", Technique::Vsm, FilterMode::SummedArea);
  }
  return e;
}

}  // namespace

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
