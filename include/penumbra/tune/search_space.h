// What `penumbra tune` searches for one technique (docs/tune.md): the parameter registry's own
// parameters and ranges (penumbra/params.h) and the render settings that shape the filtered
// shadow map — nothing else, so no hidden knob decides a result. Every dimension's values are
// text in the syntax the command line and the settings files take, so a point is applied,
// printed and saved by the same code that reads a user's settings.
#pragma once

#include <string>
#include <vector>

#include "penumbra/gl/renderer.h"
#include "penumbra/scene.h"

namespace penumbra::tune {

// How a continuous dimension maps the optimiser's unit interval onto its range.
enum class Scale {
  Linear,
  // min > 0 and max / min >= 100: equal steps per decade.
  Log,
  // min == 0 and the range is to span decades (a floor, a bias): min + (max - min) *
  // (10^(d t) - 1) / (10^d - 1) with d = kZeroLogDecades, so 0 is reachable and the first
  // decades above it are as fine as the last.
  ZeroLog,
};
inline constexpr double kZeroLogDecades = 4.0;

struct Dimension {
  std::string name;  // a technique parameter's name, or a render option's ("shadow-size", ...)
  bool isParam = true;
  bool continuous = false;
  double min = 0.0;  // continuous: the registry's range
  double max = 0.0;
  Scale scale = Scale::Linear;
  // Discrete: the values tried, in order (numeric ones ascending: the search walks them as a
  // line, categorical ones are all tried).
  std::vector<std::string> values;
  bool ordinal = false;
  std::string description;
};

// A setting the search holds at the user's value, and why.
struct FixedSetting {
  std::string name;
  std::string value;
  std::string reason;
};

struct SearchSpace {
  Technique technique = Technique::Vsm;
  std::vector<Dimension> dimensions;
  std::vector<FixedSetting> fixed;
};

// One value per dimension, as text; a continuous parameter's default may be "auto".
using Point = std::vector<std::string>;

// The space for `technique` around `base` (the user's render settings and parameters) under a
// light of kind `light`: every Real parameter continuous, every Integer and Choice parameter
// enumerated, and the shadow-map size, MSAA, normal offset, the blur's width and kernel and the
// lookup's filter where they shape this technique's map, and a directional light's cascades.
SearchSpace searchSpace(Technique technique, const gl::RenderSettings& base,
                        LightKind light = LightKind::Directional);

// The space with only the named dimensions searched (an empty list: all); the others are held
// at the user's value and listed as fixed. Names none of the dimensions has are the caller's to
// refuse (dimensionNames).
SearchSpace restrictedTo(SearchSpace space, const std::vector<std::string>& names);
std::vector<std::string> dimensionNames(const SearchSpace& space);

// The user's own values of every dimension: the search's first point, always evaluated.
Point pointOf(const SearchSpace& space, const gl::RenderSettings& settings);

// `base` with the point's values applied through the registry and the settings parsers; throws
// Error for a value the registry refuses.
gl::RenderSettings applyPoint(const SearchSpace& space, const gl::RenderSettings& base,
                              const Point& point);

// A continuous dimension's value for the optimiser's t in [0, 1], and back (clamped).
double valueAt(const Dimension& dimension, double t);
double unitOf(const Dimension& dimension, double value);
// A value as the text the registry stores without loss: 6 significant digits, which a float
// holds exactly through text and back (FLT_DIG), so a saved setting is the evaluated one.
std::string continuousText(double value);

// Multi-line description of the space for the terminal and the report.
std::string describeSpace(const SearchSpace& space);

}  // namespace penumbra::tune
