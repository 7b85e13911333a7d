// Named, documented, validated technique parameters: the one place that knows each parameter's
// name, unit, default and valid range. The CLI's --param NAME=VALUE goes through here.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/technique.h"

namespace penumbra {

enum class ParamKind { Real, Integer, Choice, SplitList };

struct ParamChoice {
  std::string_view name;
  int value;
};

struct ParamSpec {
  std::string_view name;
  ParamKind kind;
  std::string_view description;  // meaning, unit and source
  double min = 0.0;              // inclusive range for Real and Integer
  double max = 0.0;
  std::vector<ParamChoice> choices;  // for Choice
  // Real: also takes "auto", a default that follows other parameters (stored as a negative
  // sentinel the shared code resolves, e.g. MSM's moment bias by storage format).
  bool acceptsAuto = false;
};

// The parameters of one technique.
std::span<const ParamSpec> techniqueParamSpecs(Technique technique);

// The layer count of LVSM and the power CDF: setting it places that many layers uniformly, and
// setting their split list ("splits", ParamKind::SplitList) sets it to the list's length + 1.
inline constexpr std::string_view kLayerCountParam = "layers";

// Sets one parameter from text; throws Error for an unknown name (listing the valid ones), a
// malformed value, or a value out of its range (stating the range).
void setParam(Technique technique, TechniqueParams& params, std::string_view name,
              std::string_view value);
// Applies "NAME=VALUE" or "TECHNIQUE.NAME=VALUE" to every technique in `techniques` that has the
// parameter (only the named one when qualified); throws Error when none has it.
void applyParamAssignment(std::span<const Technique> techniques, TechniqueParams& params,
                          std::string_view assignment);
// The techniques that applyParamAssignment would set; throws the same errors.
std::vector<Technique> assignmentTargets(std::span<const Technique> techniques,
                                         std::string_view assignment);

// The current value as text, in the syntax setParam accepts.
std::string formatParam(Technique technique, const TechniqueParams& params, std::string_view name);

// Checks every parameter of the technique and the relations between them; throws Error.
void validateParams(Technique technique, const TechniqueParams& params);

// Multi-line help: each parameter with its range or choices and default.
std::string describeParams(Technique technique);

}  // namespace penumbra
