// The parameter registry: defaults valid, names and values checked with messages that say what
// is valid.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/params.h"

namespace penumbra {
namespace {

std::string errorOf(auto&& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Params, DefaultsAreValidForEveryTechnique) {
  const TechniqueParams params = defaultTechniqueParams();
  for (Technique t : allTechniques()) {
    EXPECT_NO_THROW(validateParams(t, params)) << techniqueId(t);
    EXPECT_FALSE(describeParams(t).empty() && !techniqueParamSpecs(t).empty());
  }
}

TEST(Params, DefaultsComeFromThePapers) {
  const TechniqueParams p = defaultTechniqueParams();
  EXPECT_EQ(p.esm.exponent, 80.0f);  // ESM paper §3.2
  EXPECT_EQ(p.csm.termCount, 16);
  EXPECT_EQ(p.csm.storage, shaders::kStorageUnorm8);    // CSM paper §4
  EXPECT_EQ(p.lvsm.storage, shaders::kStorageUnorm16);  // thesis §4.1.3
  EXPECT_EQ(p.msm.storage, shaders::kStorageUnorm16);
}

TEST(Params, UnknownTechniqueListsTheValidIds) {
  const std::string message = errorOf([] { parseTechnique("vsmm"); });
  EXPECT_NE(message.find("unknown technique 'vsmm'"), std::string::npos);
  EXPECT_NE(message.find("hard, pcf, vsm, lvsm, evsm2, evsm4, esm, csm, powercdf, msm"),
            std::string::npos);
}

TEST(Params, UnknownParameterListsTheValidNames) {
  TechniqueParams p = defaultTechniqueParams();
  const std::string message = errorOf([&] { setParam(Technique::Csm, p, "N", "4"); });
  EXPECT_NE(message.find("valid parameters: M, alpha, offset, scale, storage"), std::string::npos)
      << message;
}

TEST(Params, OutOfRangeValuesStateTheRange) {
  TechniqueParams p = defaultTechniqueParams();
  EXPECT_NE(errorOf([&] { setParam(Technique::Csm, p, "M", "17"); }).find("out of range [1, 16]"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { setParam(Technique::Vsm, p, "minVariance", "-1"); }).find("[0, 0.01]"),
            std::string::npos);
  EXPECT_EQ(p.csm.termCount, 16) << "a rejected value must not be stored";
}

TEST(Params, MalformedValuesAreRejected) {
  TechniqueParams p = defaultTechniqueParams();
  for (const char* bad : {"", "abc", "1.5x", "nan", "inf"}) {
    EXPECT_NE(errorOf([&] { setParam(Technique::Esm, p, "c", bad); }).find("not a number"),
              std::string::npos)
        << bad;
  }
  EXPECT_NE(errorOf([&] { setParam(Technique::Csm, p, "M", "4.5"); }).find("whole number"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              setParam(Technique::Vsm, p, "storage", "float64");
            }).find("valid values: float32, unorm16"),
            std::string::npos);
}

TEST(Params, ChoicesAndSplitsRoundTrip) {
  TechniqueParams p = defaultTechniqueParams();
  setParam(Technique::Pcf, p, "kernel", "gaussian");
  EXPECT_EQ(formatParam(Technique::Pcf, p, "kernel"), "gaussian");
  setParam(Technique::Lvsm, p, "splits", "0.2,0.45,0.7");
  EXPECT_EQ(p.lvsm.splits.layerCount, 4);
  EXPECT_EQ(formatParam(Technique::Lvsm, p, "splits"), "0.2,0.45,0.7");
  setParam(Technique::Lvsm, p, "layers", "2");
  EXPECT_EQ(formatParam(Technique::Lvsm, p, "splits"), "0.5");
}

TEST(Params, SplitsMustIncreaseInsideTheUnitInterval) {
  TechniqueParams p = defaultTechniqueParams();
  EXPECT_NE(errorOf([&] { setParam(Technique::Lvsm, p, "splits", "0.5,0.4"); }).find("split 2"),
            std::string::npos);
  EXPECT_THROW(setParam(Technique::Lvsm, p, "splits", "0,0.5"), Error);
  EXPECT_THROW(setParam(Technique::Lvsm, p, "splits", "0.5,1"), Error);
  EXPECT_THROW(setParam(Technique::PowerCdf, p, "splits", "0.5,,0.7"), Error);
}

// The text the documentation shows for a bound (describeParams' formatting), and a float with
// every digit (9 significant digits round-trip any float).
std::string documented(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}
std::string exact(float v) {
  std::ostringstream out;
  out << std::setprecision(9) << v;
  return out.str();
}

// Parameters whose extreme values need a partner so that the relations between parameters hold
// (validateParams checks those separately).
TechniqueParams partnersFor(Technique t, std::string_view name) {
  TechniqueParams p = defaultTechniqueParams();
  // transition <= overlap
  if (t == Technique::Lvsm && name == "transition") p.lvsm.overlap = 0.1f;
  if (t == Technique::Lvsm && name == "overlap") p.lvsm.transition = 0.0f;
  if (t == Technique::Esm && name == "c") p.esm.filterSpace = shaders::kEsmFilterLog;  // c > 88
  if (t == Technique::Csm && name == "M") p.csm.offsetScale = 0.0f;  // offset <= M - 1
  return p;
}

TEST(Params, EveryDocumentedBoundIsAcceptedAndOneStepBeyondIsNot) {
  for (Technique t : allTechniques()) {
    for (const ParamSpec& spec : techniqueParamSpecs(t)) {
      if (spec.kind != ParamKind::Real && spec.kind != ParamKind::Integer) continue;
      const std::string where = std::string(techniqueId(t)) + "." + std::string(spec.name);
      for (double bound : {spec.min, spec.max}) {
        TechniqueParams p = partnersFor(t, spec.name);
        EXPECT_NO_THROW(setParam(t, p, spec.name, documented(bound))) << where << "=" << bound;
        // The stored value must pass the registry's own validation too (it is re-checked before
        // every render): a float 0.1 is 0.100000001.
        EXPECT_NO_THROW(validateParams(t, p)) << where << "=" << bound;
      }
      std::string below, above;
      if (spec.kind == ParamKind::Real) {
        below = exact(std::nextafter(float(spec.min), -INFINITY));
        above = exact(std::nextafter(float(spec.max), INFINITY));
      } else {
        below = documented(spec.min - 1);
        above = documented(spec.max + 1);
      }
      for (const std::string& outside : {below, above}) {
        TechniqueParams p = partnersFor(t, spec.name);
        EXPECT_NE(errorOf([&] { setParam(t, p, spec.name, outside); }).find("is out of range"),
                  std::string::npos)
            << where << "=" << outside;
      }
    }
  }
}

TEST(Params, RelationsBetweenParametersAreChecked) {
  TechniqueParams p = defaultTechniqueParams();
  p.lvsm.overlap = 0.01f;
  p.lvsm.transition = 0.02f;
  EXPECT_NE(errorOf([&] { validateParams(Technique::Lvsm, p); }).find("must not exceed 'overlap'"),
            std::string::npos);
}

TEST(Params, AssignmentTargetsAreTheTechniquesAnAssignmentSets) {
  const std::vector<Technique> selected{Technique::Hard, Technique::Pcf, Technique::Vsm};
  EXPECT_EQ(assignmentTargets(selected, "constantBias=0.01"),
            (std::vector<Technique>{Technique::Hard, Technique::Pcf}));
  EXPECT_EQ(assignmentTargets(selected, "pcf.sigma=2"), std::vector<Technique>{Technique::Pcf});
  EXPECT_EQ(assignmentTargets(selected, "bleedReduction=0.2"),
            std::vector<Technique>{Technique::Vsm});
  EXPECT_THROW(assignmentTargets(selected, "pcf.sigmaa=2"), Error);
  EXPECT_THROW(assignmentTargets(selected, "c=3"), Error);  // ESM's, not selected
}

TEST(Params, AssignmentsReachEveryTechniqueThatHasTheName) {
  TechniqueParams p = defaultTechniqueParams();
  const std::vector<Technique> selected{Technique::Vsm, Technique::Lvsm, Technique::Esm};
  applyParamAssignment(selected, p, "minVariance=0.001");
  EXPECT_FLOAT_EQ(p.vsm.minVariance, 0.001f);
  EXPECT_FLOAT_EQ(p.lvsm.minVariance, 0.001f);
  applyParamAssignment(selected, p, "vsm.minVariance=0.002");
  EXPECT_FLOAT_EQ(p.vsm.minVariance, 0.002f);
  EXPECT_FLOAT_EQ(p.lvsm.minVariance, 0.001f);
  EXPECT_NE(errorOf([&] {
              applyParamAssignment(selected, p, "M=4");
            }).find("techniques that have it: csm"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { applyParamAssignment(selected, p, "nonsense"); }).find("NAME=VALUE"),
            std::string::npos);
}

}  // namespace
}  // namespace penumbra
