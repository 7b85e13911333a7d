// tune's search (penumbra/tune/search.h) on objectives whose minimum is known, through the same
// search space, text values and NLopt path as `penumbra tune`; and its units and shards.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "penumbra/error.h"
#include "penumbra/gl/settings_json.h"
#include "penumbra/params.h"
#include "penumbra/tune/search.h"
#include "penumbra/tune/tune.h"

namespace penumbra::tune {
namespace {

gl::RenderSettings baseFor(Technique t) {
  gl::RenderSettings s;
  s.technique = t;
  s.shadowMapSize = 1024;
  s.blur = {BlurKernel::Box, 2, 1.0f};
  s.filter = FilterMode::Bilinear;
  return s;
}

// A VSM objective with a minimum off every default: the variance floor at 3e-4 (in decades, as
// the floor acts), the bleeding reduction at 0.3, unorm16 storage, 2048² maps and a 7-tap box.
// Everything it reads comes through applyPoint, so the registry's parsing is on the path.
double syntheticVsmError(const gl::RenderSettings& s) {
  const double floorDecades = std::log10(std::max<double>(s.params.vsm.minVariance, 1e-9)) -
                              std::log10(3e-4);
  const double bleed = s.params.vsm.bleedReduction - 0.3;
  double e = floorDecades * floorDecades + 4.0 * bleed * bleed;
  if (s.params.vsm.storage != shaders::kStorageUnorm16) e += 1.0;
  e += std::abs(std::log2(double(s.shadowMapSize) / 2048.0));
  e += 0.1 * std::abs(double(2 * s.blur.radius + 1) - 7.0);
  if (s.blur.kernel != BlurKernel::Box) e += 0.5;
  e += 0.05 * s.normalOffsetTexels;
  return e;
}

TEST(TuneSearch, FindsAKnownOptimumThroughTheRegistrysDimensions) {
  const gl::RenderSettings base = baseFor(Technique::Vsm);
  const SearchSpace space = searchSpace(Technique::Vsm, base);
  int calls = 0;
  const SearchResult r = searchBest(
      space, pointOf(space, base),
      [&](const Point& p) {
        ++calls;
        return Trial{syntheticVsmError(applyPoint(space, base, p)), true};
      },
      {200, 4, 1e-4});
  ASSERT_TRUE(r.best);
  const gl::RenderSettings best = applyPoint(space, base, *r.best);
  // Within a tenth of a decade of the floor's optimum and 0.03 of the reduction's: NLopt stops
  // on a 1e-4 step in the unit cube, which the 4-decade scale turns into 4e-4 decades; the rest
  // is the objective's flatness near its minimum (an error of 0.01 there costs 1e-4).
  EXPECT_NEAR(std::log10(best.params.vsm.minVariance), std::log10(3e-4), 0.1);
  EXPECT_NEAR(best.params.vsm.bleedReduction, 0.3, 0.03);
  EXPECT_EQ(best.params.vsm.storage, shaders::kStorageUnorm16);
  EXPECT_EQ(best.shadowMapSize, 2048);
  EXPECT_EQ(best.blur.radius, 3);
  EXPECT_EQ(best.blur.kernel, BlurKernel::Box);
  EXPECT_LT(best.normalOffsetTexels, 0.05f);  // the bound: its lower end
  EXPECT_EQ(calls, r.evaluations);  // every distinct point once
  EXPECT_LE(r.evaluations, 200);
}

TEST(TuneSearch, ImprovesTheContinuousPartWithinTheCommandsDefaultEvaluations) {
  // `penumbra tune`'s own limits (24 settings, 3 rounds): the discrete walk takes most of them,
  // NLopt still gets enough to build BOBYQA's model and move the floor and the reduction most of
  // the way to their optimum from the defaults (1e-5 and 0: 1.5 decades and 0.3 away).
  const gl::RenderSettings base = baseFor(Technique::Vsm);
  const SearchSpace space = searchSpace(Technique::Vsm, base);
  const TuneRequest defaults;
  SearchLimits limits;
  limits.maxEvaluations = defaults.evaluations;
  const SearchResult r = searchBest(space, pointOf(space, base), [&](const Point& p) {
    return Trial{syntheticVsmError(applyPoint(space, base, p)), true};
  }, limits);
  ASSERT_TRUE(r.best);
  const gl::RenderSettings best = applyPoint(space, base, *r.best);
  EXPECT_LT(std::abs(std::log10(best.params.vsm.minVariance) - std::log10(3e-4)), 0.75);
  EXPECT_LT(std::abs(best.params.vsm.bleedReduction - 0.3), 0.15);
  EXPECT_EQ(r.evaluations, defaults.evaluations);
}

TEST(TuneSearch, FindsAMinimumAtTheRegistrysLowerBound) {
  // VSM's floor only bleeds light on a receiver the occluders do not bound (the planar scene's
  // optimum): the best floor is the registry's lower bound, 0, reachable on the zero-log scale.
  const gl::RenderSettings base = baseFor(Technique::Vsm);
  const SearchSpace space =
      restrictedTo(searchSpace(Technique::Vsm, base), {"minVariance"});
  ASSERT_EQ(space.dimensions.size(), 1u);
  const SearchResult r = searchBest(space, pointOf(space, base), [&](const Point& p) {
    const double v = applyPoint(space, base, p).params.vsm.minVariance;
    return Trial{v + 1e-3, true};
  });
  ASSERT_TRUE(r.best);
  EXPECT_LT(applyPoint(space, base, *r.best).params.vsm.minVariance, 1e-7);
}

TEST(TuneSearch, TheStartIsEvaluatedFirstAndKeptWhenNothingBeatsIt) {
  const gl::RenderSettings base = baseFor(Technique::Hard);
  const SearchSpace space = searchSpace(Technique::Hard, base);
  const Point start = pointOf(space, base);
  std::vector<Point> seen;
  const SearchResult r = searchBest(space, start, [&](const Point& p) {
    seen.push_back(p);
    return Trial{p == start ? 1.0 : 2.0, true};  // every change makes it worse
  });
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.front(), start);
  ASSERT_TRUE(r.best);
  EXPECT_EQ(*r.best, start);
  EXPECT_EQ(r.bestObjective, 1.0);
}

TEST(TuneSearch, NeverReturnsAnIneligiblePoint) {
  // The lowest objective lies over a budget (2048² maps): the search must not return it.
  const gl::RenderSettings base = baseFor(Technique::Hard);
  const SearchSpace space = searchSpace(Technique::Hard, base);
  const SearchResult r = searchBest(space, pointOf(space, base), [&](const Point& p) {
    const gl::RenderSettings s = applyPoint(space, base, p);
    return Trial{4096.0 / s.shadowMapSize, s.shadowMapSize < 2048};
  });
  ASSERT_TRUE(r.best);
  EXPECT_EQ(applyPoint(space, base, *r.best).shadowMapSize, 1024);
}

TEST(TuneSearch, NoEligiblePointGivesNoResult) {
  const gl::RenderSettings base = baseFor(Technique::Hard);
  const SearchSpace space = searchSpace(Technique::Hard, base);
  const SearchResult r = searchBest(space, pointOf(space, base),
                                    [](const Point&) { return Trial{0.0, false}; },
                                    {10, 3, 1e-3});
  EXPECT_FALSE(r.best);
  EXPECT_LE(r.evaluations, 10);
}

TEST(TuneSearch, KeepsToTheEvaluationCap) {
  const gl::RenderSettings base = baseFor(Technique::Vsm);
  const SearchSpace space = searchSpace(Technique::Vsm, base);
  std::set<Point> distinct;
  int calls = 0;
  const SearchResult r = searchBest(
      space, pointOf(space, base),
      [&](const Point& p) {
        ++calls;
        distinct.insert(p);
        return Trial{syntheticVsmError(applyPoint(space, base, p)), true};
      },
      {7, 3, 1e-3});
  EXPECT_EQ(calls, 7);
  EXPECT_EQ(distinct.size(), 7u);
  EXPECT_EQ(r.evaluations, 7);
}

TEST(TuneSearch, DoesNotRetryAValueFoundTooSlow) {
  // The driver's anisotropic filter takes seconds a frame on llvmpipe: once refused as too slow
  // where the sweep of the filter dimension tried it, later rounds skip it.
  const gl::RenderSettings base = baseFor(Technique::Vsm);
  const SearchSpace space = searchSpace(Technique::Vsm, base);
  int slowTries = 0;
  const SearchResult r = searchBest(
      space, pointOf(space, base),
      [&](const Point& p) {
        const gl::RenderSettings s = applyPoint(space, base, p);
        if (s.filter == FilterMode::AnisotropicDriver) {
          ++slowTries;
          return Trial{0.0, false, true};
        }
        return Trial{syntheticVsmError(s), true};
      },
      {200, 4, 1e-4});
  EXPECT_GE(r.rounds, 2);  // later rounds ran, and would have retried it
  EXPECT_EQ(slowTries, 1);
}

TEST(TuneSpace, ScalesMapTheUnitIntervalOntoTheRangeAndBack) {
  Dimension zeroLog{"f", true, true, 0.0, 0.01, Scale::ZeroLog, {}, false, ""};
  Dimension log{"c", true, true, 0.5, 88.0, Scale::Log, {}, false, ""};
  for (const Dimension& d : {zeroLog, log}) {
    EXPECT_DOUBLE_EQ(valueAt(d, 0.0), d.min);
    EXPECT_NEAR(valueAt(d, 1.0), d.max, 1e-12 * d.max);
    for (double t : {0.1, 0.25, 0.5, 0.9}) EXPECT_NEAR(unitOf(d, valueAt(d, t)), t, 1e-12);
  }
  // The zero-log scale gives each of its decades an equal share of the interval: a quarter of
  // the way up is a thousandth of the range (10^1 - 1 over 10^4 - 1).
  EXPECT_NEAR(valueAt(zeroLog, 0.25), 0.01 * 9.0 / 9999.0, 1e-15);
}

TEST(TuneSpace, TheUsersPointAppliesBackToTheUsersSettings) {
  for (Technique t : allTechniques()) {
    const gl::RenderSettings base = baseFor(t);
    const SearchSpace space = searchSpace(t, base);
    const gl::RenderSettings again = applyPoint(space, base, pointOf(space, base));
    EXPECT_EQ(pointOf(space, again), pointOf(space, base)) << techniqueId(t);
    EXPECT_EQ(again.shadowMapSize, base.shadowMapSize);
    EXPECT_EQ(again.blur.radius, base.blur.radius);
    EXPECT_EQ(again.filter, base.filter);
  }
}

TEST(TuneSpace, EveryRegistryParameterButTheSplitListIsSearched) {
  for (Technique t : allTechniques()) {
    const SearchSpace space = searchSpace(t, baseFor(t));
    const std::vector<std::string> names = dimensionNames(space);
    for (const ParamSpec& spec : techniqueParamSpecs(t)) {
      const bool searched =
          std::find(names.begin(), names.end(), std::string(spec.name)) != names.end();
      EXPECT_EQ(searched, spec.kind != ParamKind::SplitList) << techniqueId(t) << " " << spec.name;
    }
  }
}

TEST(TuneSpace, SearchesCascadesForDirectionalLightsOnly) {
  const gl::RenderSettings base = baseFor(Technique::Evsm4);
  const auto has = [](const SearchSpace& space, const std::string& name) {
    const std::vector<std::string> names = dimensionNames(space);
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  const SearchSpace sun = searchSpace(Technique::Evsm4, base, LightKind::Directional);
  EXPECT_TRUE(has(sun, "cascades"));
  const gl::RenderSettings cascaded = applyPoint(sun, base, [&] {
    Point p = pointOf(sun, base);
    for (size_t i = 0; i < p.size(); ++i) {
      if (sun.dimensions[i].name == "cascades") p[i] = "4";
    }
    return p;
  }());
  EXPECT_EQ(cascaded.cascades.count, 4);
  EXPECT_FALSE(has(searchSpace(Technique::Evsm4, base, LightKind::Spot), "cascades"));
  EXPECT_FALSE(has(searchSpace(Technique::Evsm4, base, LightKind::Point), "cascades"));
}

TEST(TuneSpace, AnEvaluatedSettingIsTheSavedOne) {
  // A point's continuous values are text (6 digits); applied, saved as a settings file and read
  // back as compare --settings reads it, the floats must be the evaluated ones, bit for bit.
  const gl::RenderSettings base = baseFor(Technique::Msm);
  const SearchSpace space = searchSpace(Technique::Msm, base);
  Point p = pointOf(space, base);
  int changed = 0;
  for (size_t i = 0; i < space.dimensions.size(); ++i) {
    const Dimension& d = space.dimensions[i];
    if (d.continuous) {
      p[i] = continuousText(valueAt(d, 0.123456789 + 0.1 * changed++));
    }
  }
  ASSERT_GE(changed, 3);  // momentBias, depthBias, bleedReduction, normal-offset
  gl::Settings saved;
  saved.scene = "backyard";
  saved.techniques = {Technique::Msm};
  saved.render = applyPoint(space, base, p);
  gl::Settings loaded;
  gl::applySettingsJson(gl::settingsJson(saved), "saved", loaded);
  EXPECT_EQ(pointOf(space, loaded.render), p);
  EXPECT_EQ(loaded.render.params.msm.momentBias, saved.render.params.msm.momentBias);
  EXPECT_EQ(loaded.render.params.msm.depthBias, saved.render.params.msm.depthBias);
  EXPECT_EQ(loaded.render.params.msm.bleedReduction, saved.render.params.msm.bleedReduction);
  EXPECT_EQ(loaded.render.normalOffsetTexels, saved.render.normalOffsetTexels);
}

TEST(TuneUnits, ShardsCoverEveryUnitOnce) {
  TuneRequest r;
  r.scenes = {"backyard", "planar"};
  r.techniques = {Technique::Hard, Technique::Vsm, Technique::Esm};
  const std::vector<WorkUnit> units = workUnits(r);
  ASSERT_EQ(units.size(), 6u);
  EXPECT_EQ(units[4].scene, "planar");
  EXPECT_EQ(units[4].technique, Technique::Vsm);
  std::multiset<int> seen;
  for (int k = 1; k <= 4; ++k) {
    for (const WorkUnit& u : shardUnits(units, parseShard(std::to_string(k) + "/4"))) {
      seen.insert(u.index);
    }
  }
  EXPECT_EQ(seen, (std::multiset<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_THROW(parseShard("0/4"), Error);
  EXPECT_THROW(parseShard("5/4"), Error);
  EXPECT_THROW(parseShard("1-4"), Error);
  EXPECT_THROW(parseShard("1/x"), Error);
}

TEST(TuneRequest, RefusesWhatItCannotRun) {
  TuneRequest r;
  r.techniques = {Technique::Vsm};
  EXPECT_NO_THROW(validateTuneRequest(r));
  TuneRequest bad = r;
  bad.only = {"cPositive"};  // an EVSM parameter, not VSM's
  try {
    validateTuneRequest(bad);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("minVariance"), std::string::npos) << e.what();
  }
  bad = r;
  bad.measure = ErrorMeasure::Flicker;
  bad.frames = 2;
  EXPECT_THROW(validateTuneRequest(bad), Error);
  bad = r;
  bad.searchScale = 0.0;
  EXPECT_THROW(validateTuneRequest(bad), Error);
  bad = r;
  bad.budgetMs = -1.0;
  EXPECT_THROW(validateTuneRequest(bad), Error);
  EXPECT_THROW(parseErrorMeasure("psnr"), Error);
  EXPECT_THROW(parseTarget("none"), Error);
}

}  // namespace
}  // namespace penumbra::tune
