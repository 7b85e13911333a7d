// The search space of `penumbra tune` (search_space.h): built from the parameter registry and the
// render options, applied through the same parsers as a user's settings.
#include "penumbra/tune/search_space.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gl/render_setting_values.h"
#include "penumbra/params.h"

namespace penumbra::tune {
namespace {

// Render options the search varies (isParam == false).
constexpr const char* kShadowSize = "shadow-size";
constexpr const char* kMsaa = "msaa";
constexpr const char* kBlur = "blur";
constexpr const char* kBlurKernel = "blur-kernel";
constexpr const char* kFilter = "filter";
constexpr const char* kNormalOffset = "normal-offset";
constexpr const char* kCascades = "cascades";

// Shadow-map sizes tried besides the user's: the range engines ship (a 2048² map is the usual
// top; 4096² costs 16x a 1024² light pass).
constexpr int kShadowSizes[] = {512, 1024, 2048};
// Prefilter widths tried besides the user's, in taps (1 = no blur).
constexpr int kBlurTaps[] = {1, 3, 5, 7, 9, 13};

int parseInt(const std::string& text) { return std::stoi(text); }

std::string formatInt(int v) { return std::to_string(v); }

// Numeric values, sorted and without duplicates.
std::vector<std::string> ordinalValues(std::set<int> values) {
  std::vector<std::string> out;
  for (int v : values) out.push_back(formatInt(v));
  return out;
}

// An Integer parameter's values: all of a short range; else the ends, the default and a
// doubling ladder from the minimum (min, min+1, min+3, min+7, ...), so the walk from the default
// reaches any scale in a few steps.
std::vector<std::string> integerValues(const ParamSpec& spec, int current) {
  const int lo = int(spec.min);
  const int hi = int(spec.max);
  std::set<int> values{lo, hi, std::clamp(current, lo, hi)};
  if (hi - lo <= 8) {
    for (int v = lo; v <= hi; ++v) values.insert(v);
  } else {
    for (int step = 1; lo + step - 1 < hi; step *= 2) values.insert(lo + step - 1);
  }
  return ordinalValues(values);
}

Scale realScale(const ParamSpec& spec, double current) {
  if (spec.min > 0.0 && spec.max / spec.min >= 100.0) return Scale::Log;
  // A default in the range's lowest percent: the range spans decades around it (a variance
  // floor, a bias), so linear steps would skip where the default lives.
  if (spec.min == 0.0 && current > 0.0 && current < spec.max / 100.0) return Scale::ZeroLog;
  return Scale::Linear;
}

Dimension paramDimension(Technique technique, const ParamSpec& spec,
                         const gl::RenderSettings& base) {
  Dimension d;
  d.name = std::string(spec.name);
  d.description = std::string(spec.description);
  const std::string current = formatParam(technique, base.params, spec.name);
  switch (spec.kind) {
    case ParamKind::Real:
      d.continuous = true;
      d.min = spec.min;
      d.max = spec.max;
      // "auto" values are a storage's own floor, in the range's lowest decades.
      d.scale = current == "auto" ? Scale::ZeroLog : realScale(spec, std::stod(current));
      break;
    case ParamKind::Integer:
      d.values = integerValues(spec, parseInt(current));
      d.ordinal = true;
      break;
    case ParamKind::Choice:
      for (const ParamChoice& c : spec.choices) d.values.emplace_back(c.name);
      break;
    case ParamKind::SplitList:
      break;  // not searched (see searchSpace)
  }
  return d;
}

Dimension renderDimension(std::string name, std::string description,
                          std::vector<std::string> values, bool ordinal) {
  Dimension d;
  d.name = std::move(name);
  d.isParam = false;
  d.description = std::move(description);
  d.values = std::move(values);
  d.ordinal = ordinal;
  return d;
}

std::string renderValue(const gl::RenderSettings& s, const std::string& name) {
  if (name == kShadowSize) return formatInt(s.shadowMapSize);
  if (name == kMsaa) return formatInt(s.msaaSamples);
  if (name == kBlur) return formatInt(2 * s.blur.radius + 1);
  if (name == kBlurKernel) return std::string(gl::blurKernelName(s.blur.kernel));
  if (name == kFilter) return std::string(filterModeName(s.filter));
  if (name == kNormalOffset) return continuousText(s.normalOffsetTexels);
  if (name == kCascades) return formatInt(s.cascades.count);
  throw Error("tune: unknown render dimension '" + name + "'");
}

void applyRenderValue(gl::RenderSettings& s, const std::string& name, const std::string& value) {
  if (name == kShadowSize) {
    s.shadowMapSize = parseInt(value);
  } else if (name == kMsaa) {
    s.msaaSamples = parseInt(value);
  } else if (name == kBlur) {
    s.blur.radius = gl::blurRadiusOfTaps(parseInt(value));
    // The sigma follows the width as the command line's default does (a fixed setting).
    s.blur.sigma = gl::defaultBlurSigma(s.blur.radius);
  } else if (name == kBlurKernel) {
    s.blur.kernel = gl::parseBlurKernel(value);
  } else if (name == kFilter) {
    s.filter = parseFilterMode(value);
  } else if (name == kCascades) {
    s.cascades.count = parseInt(value);
  } else if (name == kNormalOffset) {
    s.normalOffsetTexels = std::stof(value);
  } else {
    throw Error("tune: unknown render dimension '" + name + "'");
  }
}

}  // namespace

std::string continuousText(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

double valueAt(const Dimension& d, double t) {
  t = std::clamp(t, 0.0, 1.0);
  switch (d.scale) {
    case Scale::Linear: return d.min + (d.max - d.min) * t;
    case Scale::Log: return d.min * std::pow(d.max / d.min, t);
    case Scale::ZeroLog:
      return d.min + (d.max - d.min) * (std::pow(10.0, kZeroLogDecades * t) - 1.0) /
                         (std::pow(10.0, kZeroLogDecades) - 1.0);
  }
  return d.min;
}

double unitOf(const Dimension& d, double value) {
  value = std::clamp(value, d.min, d.max);
  double t = 0.0;
  switch (d.scale) {
    case Scale::Linear: t = d.max > d.min ? (value - d.min) / (d.max - d.min) : 0.0; break;
    case Scale::Log: t = std::log(value / d.min) / std::log(d.max / d.min); break;
    case Scale::ZeroLog:
      t = std::log10(1.0 + (value - d.min) / (d.max - d.min) *
                               (std::pow(10.0, kZeroLogDecades) - 1.0)) /
          kZeroLogDecades;
      break;
  }
  return std::clamp(t, 0.0, 1.0);
}

SearchSpace searchSpace(Technique technique, const gl::RenderSettings& base, LightKind light) {
  SearchSpace space;
  space.technique = technique;
  for (const ParamSpec& spec : techniqueParamSpecs(technique)) {
    if (spec.kind == ParamKind::SplitList) {
      space.fixed.push_back({std::string(spec.name),
                             formatParam(technique, base.params, spec.name),
                             "an explicit split list; the search varies the layer count and the "
                             "placement, which place the splits"});
      continue;
    }
    space.dimensions.push_back(paramDimension(technique, spec, base));
  }

  std::set<int> sizes(std::begin(kShadowSizes), std::end(kShadowSizes));
  sizes.insert(base.shadowMapSize);
  space.dimensions.push_back(renderDimension(
      kShadowSize, "shadow-map texels per side", ordinalValues(sizes), true));
  space.dimensions.push_back(renderDimension(kMsaa, "light-pass samples per texel",
                                             ordinalValues({1, 2, 4, base.msaaSamples}), true));
  if (prefiltersChannels(technique)) {
    std::set<int> taps(std::begin(kBlurTaps), std::end(kBlurTaps));
    taps.insert(2 * base.blur.radius + 1);
    space.dimensions.push_back(
        renderDimension(kBlur, "prefilter width in taps (1: none)", ordinalValues(taps), true));
    space.dimensions.push_back(renderDimension(
        kBlurKernel, "prefilter kernel",
        {std::string(gl::blurKernelName(BlurKernel::Box)),
         std::string(gl::blurKernelName(BlurKernel::Gaussian))},
        false));
    std::vector<std::string> filters;
    for (FilterMode m : {FilterMode::Point, FilterMode::Bilinear, FilterMode::Trilinear,
                         FilterMode::Anisotropic, FilterMode::SummedArea,
                         FilterMode::AnisotropicDriver}) {
      filters.emplace_back(filterModeName(m));
    }
    space.dimensions.push_back(
        renderDimension(kFilter, "the lookup's filter", std::move(filters), false));
    space.fixed.push_back({"blur-sigma", "half the radius, at least 0.5",
                           "follows the blur's width as the command line's default does"});
    space.fixed.push_back({"aniso", formatInt(base.anisotropy),
                           "the user's; it shapes the anisotropic filters only"});
  } else {
    space.fixed.push_back({"blur, blur-kernel, filter", "the user's",
                           techniqueId(technique) == std::string_view("pcf")
                               ? "PCF filters the test results with its own kernel parameters"
                               : "the hard test does not filter"});
  }
  Dimension offset;
  offset.name = kNormalOffset;
  offset.isParam = false;
  offset.continuous = true;
  offset.min = 0.0;
  offset.max = gl::kMaxNormalOffsetTexels;
  offset.description = "normal-offset bias, shadow-map texels";
  space.dimensions.push_back(offset);
  if (light == LightKind::Directional) {
    // The cascades split the view's depth range; every layout is measured on the same pixels
    // (the target's, fixed by the given setting), so one that leaves pixels unshadowed pays.
    space.dimensions.push_back(renderDimension(kCascades, "cascaded shadow maps (1: one map)",
                                               ordinalValues({1, 2, 4, base.cascades.count}),
                                               true));
  } else {
    space.fixed.push_back({kCascades, formatInt(base.cascades.count),
                           "cascades split a directional light's view; this light is not one"});
  }
  space.fixed.push_back({"width, height", formatInt(base.width) + "x" + formatInt(base.height),
                         "the frame measured"});
  space.fixed.push_back({"ambient", continuousText(base.ambient), "shading, not the shadow"});
  return space;
}

SearchSpace restrictedTo(SearchSpace space, const std::vector<std::string>& names) {
  if (names.empty()) return space;
  std::vector<Dimension> kept;
  for (Dimension& d : space.dimensions) {
    if (std::find(names.begin(), names.end(), d.name) != names.end()) {
      kept.push_back(std::move(d));
    } else {
      space.fixed.push_back({d.name, "the user's", "not among --only's dimensions"});
    }
  }
  space.dimensions = std::move(kept);
  return space;
}

std::vector<std::string> dimensionNames(const SearchSpace& space) {
  std::vector<std::string> names;
  for (const Dimension& d : space.dimensions) names.push_back(d.name);
  return names;
}

Point pointOf(const SearchSpace& space, const gl::RenderSettings& settings) {
  Point p;
  for (const Dimension& d : space.dimensions) {
    p.push_back(d.isParam ? formatParam(space.technique, settings.params, d.name)
                          : renderValue(settings, d.name));
  }
  return p;
}

gl::RenderSettings applyPoint(const SearchSpace& space, const gl::RenderSettings& base,
                              const Point& point) {
  if (point.size() != space.dimensions.size()) {
    throw Error("tune: a point of " + std::to_string(point.size()) + " values for " +
                std::to_string(space.dimensions.size()) + " dimensions");
  }
  gl::RenderSettings s = base;
  s.technique = space.technique;
  for (size_t i = 0; i < point.size(); ++i) {
    const Dimension& d = space.dimensions[i];
    if (d.isParam) {
      setParam(space.technique, s.params, d.name, point[i]);
    } else {
      applyRenderValue(s, d.name, point[i]);
    }
  }
  return s;
}

std::string describeSpace(const SearchSpace& space) {
  std::ostringstream out;
  out << techniqueId(space.technique) << ": " << space.dimensions.size() << " dimensions\n";
  for (const Dimension& d : space.dimensions) {
    out << "  " << (d.isParam ? "param " : "") << d.name << ": ";
    if (d.continuous) {
      out << "[" << continuousText(d.min) << ", " << continuousText(d.max) << "] "
          << (d.scale == Scale::Linear ? "linear" : d.scale == Scale::Log ? "log" : "zero-log");
    } else {
      for (size_t i = 0; i < d.values.size(); ++i) out << (i ? (d.ordinal ? ", " : " | ") : "") << d.values[i];
    }
    out << "  (" << d.description << ")\n";
  }
  for (const FixedSetting& f : space.fixed) {
    out << "  fixed " << f.name << " = " << f.value << ": " << f.reason << "\n";
  }
  return out.str();
}

}  // namespace penumbra::tune
