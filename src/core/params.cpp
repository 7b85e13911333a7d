// The parameter registry: names, ranges, choices and accessors of every technique parameter.
#include "penumbra/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/shared/technique_params.h"

namespace penumbra {
namespace {

using shaders::LayerSplits;

// A spec plus where its value lives in TechniqueParams; exactly one accessor is set.
struct ParamBinding {
  ParamSpec spec;
  float* (*real)(TechniqueParams&) = nullptr;
  int* (*integer)(TechniqueParams&) = nullptr;
  LayerSplits* (*splits)(TechniqueParams&) = nullptr;
  float autoSentinel = 0.0f;  // the stored value of "auto" when spec.acceptsAuto
};

ParamBinding real(std::string_view name, std::string_view doc, double lo, double hi,
                  float* (*field)(TechniqueParams&)) {
  ParamBinding b{ParamSpec{name, ParamKind::Real, doc, lo, hi, {}}};
  b.real = field;
  return b;
}

// A Real parameter that also takes "auto", stored as `sentinel` (below its range).
ParamBinding automatic(ParamBinding b, float sentinel) {
  b.spec.acceptsAuto = true;
  b.autoSentinel = sentinel;
  return b;
}

ParamBinding integer(std::string_view name, std::string_view doc, int lo, int hi,
                     int* (*field)(TechniqueParams&)) {
  ParamBinding b{ParamSpec{name, ParamKind::Integer, doc, double(lo), double(hi), {}}};
  b.integer = field;
  return b;
}

ParamBinding choice(std::string_view name, std::string_view doc, std::vector<ParamChoice> choices,
                    int* (*field)(TechniqueParams&)) {
  ParamBinding b{ParamSpec{name, ParamKind::Choice, doc, 0.0, 0.0, std::move(choices)}};
  b.integer = field;
  return b;
}

ParamBinding splitList(std::string_view doc, LayerSplits* (*field)(TechniqueParams&)) {
  ParamBinding b{ParamSpec{"splits", ParamKind::SplitList, doc, 0.0, 1.0, {}}};
  b.splits = field;
  return b;
}

const ParamChoice kFloat32{"float32", shaders::kStorageFloat32};
const ParamChoice kFloat16{"float16", shaders::kStorageFloat16};
const ParamChoice kUnorm16{"unorm16", shaders::kStorageUnorm16};
const ParamChoice kUnorm8{"unorm8", shaders::kStorageUnorm8};

constexpr std::string_view kMinVarianceDoc =
    "variance floor against numerical trouble, linear depth^2 units (thesis §3.3)";
constexpr std::string_view kEvsmMinVarianceDoc =
    "variance floor against numerical trouble, linear depth^2 units, scaled by each warp's slope "
    "(thesis §3.3)";
// LVSM's Chebyshev test runs on the layer's warped depth (thesis eq. 4.2), stretched by
// 1 / (layer width): a floor f there is f * width^2 in linear depth (1/13.7 of it for an inner
// layer of 4 uniform ones with the default overlap, width 0.27).
constexpr std::string_view kLvsmMinVarianceDoc =
    "variance floor against numerical trouble, in the layer's warped depth^2 (thesis eq. 4.2: "
    "depth stretched by 1/layer width), i.e. value * width^2 in linear depth^2";
constexpr std::string_view kBleedDoc =
    "light-bleeding reduction: clamp the tail below this and rescale (thesis §3.4); 0 = off";
constexpr std::string_view kConstantBiasDoc = "constant depth bias, linear depth units";
constexpr std::string_view kSlopeBiasDoc = "slope-scaled depth bias, times depth slope per texel";
constexpr std::string_view kLayersDoc =
    "number of depth layers L; setting it places the L-1 splits uniformly";
constexpr std::string_view kSplitsDoc =
    "interior split depths s_1..s_{L-1}, comma-separated, increasing in (0,1); sets L (empty: "
    "one layer)";

std::vector<ParamBinding> bindingsFor(Technique technique) {
  switch (technique) {
    case Technique::Hard:
      return {
          real("constantBias", kConstantBiasDoc, 0.0, 0.1,
               [](TechniqueParams& p) { return &p.hard.constantBias; }),
          real("slopeBias", kSlopeBiasDoc, 0.0, 10.0,
               [](TechniqueParams& p) { return &p.hard.slopeScaledBias; }),
      };
    case Technique::Pcf:
      return {
          choice("kernel", "filter kernel (thesis ch. 2)",
                 {{"box", shaders::kKernelBox},
                  {"gaussian", shaders::kKernelGaussian},
                  {"bilinear", shaders::kKernelBilinear},
                  {"gaussianBilinear", shaders::kKernelGaussianBilinear}},
                 [](TechniqueParams& p) { return &p.pcf.kernel; }),
          integer("radius", "taps each side of the centre: (2r+1)^2 taps (the blur's range)", 0,
                  shaders::kMaxBlurRadius, [](TechniqueParams& p) { return &p.pcf.radius; }),
          real("sigma", "Gaussian kernel standard deviation, texels (the blur's range)", 0.01, 64.0,
               [](TechniqueParams& p) { return &p.pcf.sigma; }),
          choice("receiverPlane", "receiver-plane depth bias: each tap follows the receiver plane",
                 {{"off", 0}, {"on", 1}}, [](TechniqueParams& p) { return &p.pcf.receiverPlane; }),
          real("constantBias", kConstantBiasDoc, 0.0, 0.1,
               [](TechniqueParams& p) { return &p.pcf.bias.constantBias; }),
          real("slopeBias", kSlopeBiasDoc, 0.0, 10.0,
               [](TechniqueParams& p) { return &p.pcf.bias.slopeScaledBias; }),
      };
    case Technique::Vsm:
      return {
          real("minVariance", kMinVarianceDoc, 0.0, 0.01,
               [](TechniqueParams& p) { return &p.vsm.minVariance; }),
          real("bleedReduction", kBleedDoc, 0.0, 0.99,
               [](TechniqueParams& p) { return &p.vsm.bleedReduction; }),
          choice("storage", "moment storage format", {kFloat32, kUnorm16},
                 [](TechniqueParams& p) { return &p.vsm.storage; }),
      };
    case Technique::Lvsm:
      return {
          integer(kLayerCountParam, kLayersDoc, 1, shaders::kMaxLayers,
                  [](TechniqueParams& p) { return &p.lvsm.splits.layerCount; }),
          splitList(kSplitsDoc, [](TechniqueParams& p) { return &p.lvsm.splits; }),
          real("overlap", "layer overlap delta, depth units (thesis §4.1.1)", 0.0, 0.1,
               [](TechniqueParams& p) { return &p.lvsm.overlap; }),
          real("transition", "blend width below each split, depth units; at most overlap", 0.0, 0.1,
               [](TechniqueParams& p) { return &p.lvsm.transition; }),
          real("minVariance", kLvsmMinVarianceDoc, 0.0, 0.01,
               [](TechniqueParams& p) { return &p.lvsm.minVariance; }),
          real("bleedReduction", kBleedDoc, 0.0, 0.99,
               [](TechniqueParams& p) { return &p.lvsm.bleedReduction; }),
          choice("storage", "per-layer moment storage (thesis: unorm16)", {kUnorm16, kFloat32},
                 [](TechniqueParams& p) { return &p.lvsm.storage; }),
          choice("placement",
                 "split placement (thesis §4.1.2): lloyd relaxation per frame, uniform, or fixed "
                 "(the given splits; setting splits selects it)",
                 {{"lloyd", shaders::kLayerPlacementLloyd},
                  {"uniform", shaders::kLayerPlacementUniform},
                  {"fixed", shaders::kLayerPlacementFixed}},
                 [](TechniqueParams& p) { return &p.lvsm.placement; }),
          integer("lloydIterations", "Lloyd relaxation steps for a still image", 1, 64,
                  [](TechniqueParams& p) { return &p.lvsm.lloydIterations; }),
      };
    case Technique::Evsm2:
    case Technique::Evsm4: {
      std::vector<ParamBinding> b{
          real("cPositive", "positive warp exponent c+, clamped to 42 (fp32) or 5.54 (fp16)", 0.5,
               42.0, [](TechniqueParams& p) { return &p.evsm.positiveExponent; }),
      };
      if (technique == Technique::Evsm4) {
        b.push_back(real("cNegative",
                         "negative warp exponent c-, clamped to 42 (fp32) or 5.54 (fp16)", 0.5,
                         42.0, [](TechniqueParams& p) { return &p.evsm.negativeExponent; }));
      }
      b.push_back(real("minVariance", kEvsmMinVarianceDoc, 0.0, 0.01,
                       [](TechniqueParams& p) { return &p.evsm.minVariance; }));
      b.push_back(real("bleedReduction", kBleedDoc, 0.0, 0.99,
                       [](TechniqueParams& p) { return &p.evsm.bleedReduction; }));
      b.push_back(choice("storage", "warped moment storage", {kFloat32, kFloat16},
                         [](TechniqueParams& p) { return &p.evsm.storage; }));
      return b;
    }
    case Technique::Esm:
      return {
          real("c", "exponent c (ESM paper §3.2: 80 for fp32); at most 88 with linear filtering",
               0.01, 10000.0, [](TechniqueParams& p) { return &p.esm.exponent; }),
          choice("filtering", "filter exp(cz) linearly, or z in log space (Salvi)",
                 {{"linear", shaders::kEsmFilterLinear}, {"log", shaders::kEsmFilterLog}},
                 [](TechniqueParams& p) { return &p.esm.filterSpace; }),
          real("threshold", "epsilon of threshold failure classification (ESM paper §3.3)", 0.0,
               10.0, [](TechniqueParams& p) { return &p.esm.threshold; }),
          choice("classifier",
                 "failure classification (ESM paper §3.3), failing pixels shaded by the "
                 "fallback: threshold (the paper's choice), zmax (max-depth pyramid), or none",
                 {{"threshold", shaders::kEsmClassifyThreshold},
                  {"zmax", shaders::kEsmClassifyZmax},
                  {"none", shaders::kEsmClassifyNone}},
                 [](TechniqueParams& p) { return &p.esm.classifier; }),
          real("zmaxOffset", "offset added to the receiver depth for Z-max classification", 0.0,
               0.1, [](TechniqueParams& p) { return &p.esm.zmaxOffset; }),
          choice("fallback",
                 "shading of failing pixels: pcf (PCF of the unfiltered depth with the "
                 "prefilter's kernel) or paper (2x2 test on the prefiltered ESM, §3.3)",
                 {{"pcf", shaders::kEsmFallbackPcf}, {"paper", shaders::kEsmFallbackPaper}},
                 [](TechniqueParams& p) { return &p.esm.fallback; }),
      };
    case Technique::Csm:
      return {
          integer("M", "Fourier terms M (CSM paper §3.1); M/2 RGBA textures", 1,
                  shaders::kCsmMaxTerms, [](TechniqueParams& p) { return &p.csm.termCount; }),
          real("alpha", "ringing attenuation exp(-alpha (k/M)^2) (CSM §3.2.1); 0 = off", 0.0, 20.0,
               [](TechniqueParams& p) { return &p.csm.attenuation; }),
          real("offset", "receiver offset in units of 1/(2M) (CSM §3.2.2), at most M - 1; 0 = off",
               0.0, 4.0, [](TechniqueParams& p) { return &p.csm.offsetScale; }),
          real("scale", "reconstruction scale (CSM §3.2.2 uses 2); 1 = off", 1.0, 4.0,
               [](TechniqueParams& p) { return &p.csm.scale; }),
          choice("storage", "basis storage (paper: unorm8)", {kUnorm8, kFloat16, kFloat32},
                 [](TechniqueParams& p) { return &p.csm.storage; }),
      };
    case Technique::PowerCdf:
      return {
          integer(kLayerCountParam, kLayersDoc, 1, shaders::kMaxLayers,
                  [](TechniqueParams& p) { return &p.powerCdf.splits.layerCount; }),
          splitList(kSplitsDoc, [](TechniqueParams& p) { return &p.powerCdf.splits; }),
          real("depthBias", "subtracted from the receiver depth against storage rounding", 0.0, 0.1,
               [](TechniqueParams& p) { return &p.powerCdf.depthBias; }),
          real("overlap", "layer intervals widened by this on the inner sides (as LVSM's delta)",
               0.0, 0.1, [](TechniqueParams& p) { return &p.powerCdf.overlap; }),
          choice("storage", "min/max/mean storage (Gumbau §4: 16 bits suffice)",
                 {kFloat32, kFloat16}, [](TechniqueParams& p) { return &p.powerCdf.storage; }),
      };
    case Technique::Msm:
      return {
          automatic(real("momentBias",
                         "moment bias alpha; auto: the storage's, 3e-5 for unorm16 and 3e-6 for "
                         "float32 (msm notes)",
                         0.0, 0.01, [](TechniqueParams& p) { return &p.msm.momentBias; }),
                    shaders::kMsmMomentBiasAuto),
          real("depthBias", "subtracted from the receiver depth, linear depth units", 0.0, 0.1,
               [](TechniqueParams& p) { return &p.msm.depthBias; }),
          real("bleedReduction", kBleedDoc, 0.0, 0.99,
               [](TechniqueParams& p) { return &p.msm.bleedReduction; }),
          choice("storage", "moment storage: optimised 16-bit quantisation or float32",
                 {kUnorm16, kFloat32}, [](TechniqueParams& p) { return &p.msm.storage; }),
      };
  }
  return {};
}

const std::vector<ParamBinding>& bindings(Technique technique) {
  checkTechnique(technique);
  static const std::vector<std::vector<ParamBinding>> all = [] {
    std::vector<std::vector<ParamBinding>> table;
    for (Technique t : allTechniques()) table.push_back(bindingsFor(t));
    return table;
  }();
  return all[size_t(technique)];
}

std::string nameList(Technique technique) {
  std::string list;
  for (const ParamBinding& b : bindings(technique)) {
    if (!list.empty()) list += ", ";
    list += b.spec.name;
  }
  return list.empty() ? "(none)" : list;
}

const ParamBinding& findBinding(Technique technique, std::string_view name) {
  for (const ParamBinding& b : bindings(technique)) {
    if (b.spec.name == name) return b;
  }
  throw Error("unknown parameter '" + std::string(name) + "' for technique '" +
              std::string(techniqueId(technique)) + "'; valid parameters: " + nameList(technique));
}

std::string context(Technique technique, std::string_view name) {
  return std::string(techniqueId(technique)) + " parameter '" + std::string(name) + "'";
}

std::string formatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

double parseNumber(Technique technique, std::string_view name, std::string_view text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
    throw Error(context(technique, name) + ": '" + std::string(text) + "' is not a number");
  }
  return value;
}

// Real parameters are stored as float, so they are compared in float with the bounds rounded to
// float: a documented bound such as 0.1 is itself accepted (as 0.100000001f, which a double
// comparison with 0.1 rejects), and one float step beyond it is not.
void checkRange(const ParamSpec& spec, Technique technique, double value) {
  const bool real = spec.kind == ParamKind::Real;
  const double v = real ? double(float(value)) : value;
  const double lo = real ? double(float(spec.min)) : spec.min;
  const double hi = real ? double(float(spec.max)) : spec.max;
  if (v < lo || v > hi) {
    throw Error(context(technique, spec.name) + ": " + formatNumber(value) + " is out of range [" +
                formatNumber(spec.min) + ", " + formatNumber(spec.max) + "]");
  }
}

// An empty list is one layer (no interior split), as formatSplits writes it.
LayerSplits parseSplits(Technique technique, std::string_view text) {
  std::vector<float> values;
  size_t start = 0;
  while (!text.empty() && start <= text.size()) {
    size_t comma = text.find(',', start);
    std::string_view item =
        text.substr(start, comma == std::string_view::npos ? text.npos : comma - start);
    values.push_back(float(parseNumber(technique, "splits", item)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (values.size() > size_t(shaders::kMaxLayers - 1)) {
    throw Error(context(technique, "splits") + ": at most " +
                std::to_string(shaders::kMaxLayers - 1) + " splits");
  }
  LayerSplits splits = shaders::uniformLayerSplits(int(values.size()) + 1);
  for (size_t k = 0; k < values.size(); ++k) splits.interior[k / 4][k % 4] = values[k];
  return splits;
}

void validateSplits(Technique technique, const LayerSplits& splits) {
  float previous = 0.0f;
  for (int i = 1; i < splits.layerCount; ++i) {
    float s = shaders::layerSplit(splits, i);
    if (!(s > previous && s < 1.0f)) {
      throw Error(context(technique, "splits") + ": split " + std::to_string(i) + " (" +
                  formatNumber(s) + ") must be above the previous one (" + formatNumber(previous) +
                  ") and below 1");
    }
    previous = s;
  }
}

std::string formatSplits(const LayerSplits& splits) {
  std::string text;
  for (int i = 1; i < splits.layerCount; ++i) {
    if (!text.empty()) text += ",";
    text += formatNumber(shaders::layerSplit(splits, i));
  }
  return text;
}

}  // namespace

std::span<const ParamSpec> techniqueParamSpecs(Technique technique) {
  checkTechnique(technique);
  static const std::vector<std::vector<ParamSpec>> all = [] {
    std::vector<std::vector<ParamSpec>> table;
    for (Technique t : allTechniques()) {
      std::vector<ParamSpec> specs;
      for (const ParamBinding& b : bindings(t)) specs.push_back(b.spec);
      table.push_back(std::move(specs));
    }
    return table;
  }();
  return all[size_t(technique)];
}

void setParam(Technique technique, TechniqueParams& params, std::string_view name,
              std::string_view value) {
  const ParamBinding& b = findBinding(technique, name);
  switch (b.spec.kind) {
    case ParamKind::Real: {
      if (b.spec.acceptsAuto && value == "auto") {
        *b.real(params) = b.autoSentinel;
        break;
      }
      double v = parseNumber(technique, name, value);
      checkRange(b.spec, technique, v);
      *b.real(params) = float(v);
      break;
    }
    case ParamKind::Integer: {
      double v = parseNumber(technique, name, value);
      if (v != std::floor(v)) {
        throw Error(context(technique, name) + ": '" + std::string(value) +
                    "' is not a whole number");
      }
      checkRange(b.spec, technique, v);
      *b.integer(params) = int(v);
      // Setting a layer count places that many layers uniformly.
      if (name == kLayerCountParam) {
        LayerSplits* splits = findBinding(technique, "splits").splits(params);
        *splits = shaders::uniformLayerSplits(int(v));
      }
      break;
    }
    case ParamKind::Choice: {
      std::string valid;
      for (const ParamChoice& c : b.spec.choices) {
        if (c.name == value) {
          *b.integer(params) = c.value;
          return;
        }
        valid += (valid.empty() ? "" : ", ") + std::string(c.name);
      }
      throw Error(context(technique, name) + ": unknown value '" + std::string(value) +
                  "'; valid values: " + valid);
    }
    case ParamKind::SplitList: {
      LayerSplits splits = parseSplits(technique, value);
      validateSplits(technique, splits);
      *b.splits(params) = splits;
      // Given splits are used as given.
      if (technique == Technique::Lvsm) params.lvsm.placement = shaders::kLayerPlacementFixed;
      break;
    }
  }
}

namespace {

struct ParsedAssignment {
  std::string_view name, value;
  std::vector<Technique> targets;
};

ParsedAssignment parseAssignment(std::span<const Technique> techniques,
                                 std::string_view assignment) {
  size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0) {
    throw Error("parameter '" + std::string(assignment) +
                "' must be NAME=VALUE or TECHNIQUE.NAME=VALUE");
  }
  ParsedAssignment parsed{assignment.substr(0, eq), assignment.substr(eq + 1), {}};
  size_t dot = parsed.name.find('.');
  if (dot != std::string_view::npos) {
    parsed.targets.push_back(parseTechnique(parsed.name.substr(0, dot)));
    parsed.name = parsed.name.substr(dot + 1);
    findBinding(parsed.targets[0], parsed.name);  // throws for an unknown name
    return parsed;
  }
  auto has = [&](Technique t) {
    const auto& b = bindings(t);
    return std::any_of(b.begin(), b.end(),
                       [&](const ParamBinding& x) { return x.spec.name == parsed.name; });
  };
  for (Technique t : techniques) {
    if (has(t)) parsed.targets.push_back(t);
  }
  if (parsed.targets.empty()) {
    std::string owners;
    for (Technique t : allTechniques()) {
      if (has(t)) owners += (owners.empty() ? "" : ", ") + std::string(techniqueId(t));
    }
    throw Error("parameter '" + std::string(parsed.name) +
                "' belongs to none of the selected techniques" +
                (owners.empty() ? std::string(" nor to any other")
                                : "; techniques that have it: " + owners));
  }
  return parsed;
}

}  // namespace

std::vector<Technique> assignmentTargets(std::span<const Technique> techniques,
                                         std::string_view assignment) {
  return parseAssignment(techniques, assignment).targets;
}

void applyParamAssignment(std::span<const Technique> techniques, TechniqueParams& params,
                          std::string_view assignment) {
  const ParsedAssignment parsed = parseAssignment(techniques, assignment);
  for (Technique t : parsed.targets) setParam(t, params, parsed.name, parsed.value);
}

std::string formatParam(Technique technique, const TechniqueParams& params, std::string_view name) {
  const ParamBinding& b = findBinding(technique, name);
  TechniqueParams p = params;  // the accessors take a mutable block; read a copy
  switch (b.spec.kind) {
    case ParamKind::Real:
      if (b.spec.acceptsAuto && *b.real(p) == b.autoSentinel) return "auto";
      return formatNumber(*b.real(p));
    case ParamKind::Integer: return std::to_string(*b.integer(p));
    case ParamKind::Choice:
      for (const ParamChoice& c : b.spec.choices) {
        if (c.value == *b.integer(p)) return std::string(c.name);
      }
      return "invalid(" + std::to_string(*b.integer(p)) + ")";
    case ParamKind::SplitList: return formatSplits(*b.splits(p));
  }
  return {};
}

void validateParams(Technique technique, const TechniqueParams& params) {
  TechniqueParams p = params;  // the accessors take a mutable block; read a copy
  for (const ParamBinding& b : bindings(technique)) {
    switch (b.spec.kind) {
      case ParamKind::Real: {
        float v = *b.real(p);
        if (!std::isfinite(v)) throw Error(context(technique, b.spec.name) + ": not finite");
        if (!(b.spec.acceptsAuto && v == b.autoSentinel)) checkRange(b.spec, technique, v);
        break;
      }
      case ParamKind::Integer: checkRange(b.spec, technique, *b.integer(p)); break;
      case ParamKind::Choice: {
        int v = *b.integer(p);
        bool known = std::any_of(b.spec.choices.begin(), b.spec.choices.end(),
                                 [v](const ParamChoice& c) { return c.value == v; });
        if (!known)
          throw Error(context(technique, b.spec.name) + ": invalid value " + std::to_string(v));
        break;
      }
      case ParamKind::SplitList: validateSplits(technique, *b.splits(p)); break;
    }
  }
  if (technique == Technique::Lvsm && params.lvsm.transition > params.lvsm.overlap) {
    throw Error("lvsm parameter 'transition' (" + formatNumber(params.lvsm.transition) +
                ") must not exceed 'overlap' (" + formatNumber(params.lvsm.overlap) +
                "): the blend reads the next layer inside its overlap (thesis §4.1.1)");
  }
  if (technique == Technique::Csm && params.csm.offsetScale > float(params.csm.termCount - 1)) {
    // The depth scale kappa = 1 - (1 + offset) / (2M) keeps every depth pair clear of the series'
    // wrap at t = 1 only while it is at least 1/2 (docs/techniques.md, CSM depth scale).
    throw Error("csm parameter 'offset' (" + formatNumber(params.csm.offsetScale) +
                ") must not exceed M - 1 (" + std::to_string(params.csm.termCount - 1) +
                " for M = " + std::to_string(params.csm.termCount) +
                "): a larger offset wraps lit receivers in front of far occluders onto the "
                "shadowed half of the Fourier series");
  }
  if (technique == Technique::Esm && params.esm.filterSpace == shaders::kEsmFilterLinear &&
      params.esm.exponent > shaders::kEsmMaxLinearExponent) {
    throw Error("esm parameter 'c' (" + formatNumber(params.esm.exponent) +
                ") is above 88, the largest exp(c z) fp32 holds; use filtering=log for larger c");
  }
}

std::string describeParams(Technique technique) {
  std::ostringstream out;
  const TechniqueParams defaults = defaultTechniqueParams();
  for (const ParamBinding& b : bindings(technique)) {
    out << "  " << b.spec.name << "  ";
    switch (b.spec.kind) {
      case ParamKind::Real:
      case ParamKind::Integer:
        out << "[" << formatNumber(b.spec.min) << ", " << formatNumber(b.spec.max) << "]";
        if (b.spec.acceptsAuto) out << " or auto";
        break;
      case ParamKind::Choice: {
        std::string list;
        for (const ParamChoice& c : b.spec.choices)
          list += (list.empty() ? "" : "|") + std::string(c.name);
        out << list;
        break;
      }
      case ParamKind::SplitList: out << "s1,s2,..."; break;
    }
    out << "  default " << formatParam(technique, defaults, b.spec.name) << "\n      "
        << b.spec.description << "\n";
  }
  return out.str();
}

}  // namespace penumbra
