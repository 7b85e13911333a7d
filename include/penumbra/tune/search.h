// The search of `penumbra tune` over one technique's space (search_space.h), independent of what
// an evaluation measures, so a test drives it with an objective whose minimum is known.
//
// Mixed discrete and continuous, bounded, derivative-free (docs/tune.md):
//  1. the start (the user's setting) is evaluated first, always;
//  2. each round walks the discrete dimensions one at a time from the current point — an ordinal
//     one (sizes, widths, counts) as a line, outward from the current value while the objective
//     improves; a categorical one (storage, kernel, filter, classifier) by trying every value —
//     and keeps the best value of each;
//  3. then NLopt optimises the continuous dimensions together from the current point, on the
//     unit cube of their scales (BOBYQA, or Sbplx for a single dimension), within the round's
//     share of the evaluations;
//  4. rounds repeat while one improved the best and evaluations remain.
// The result is the best eligible point seen, so it is never worse than the start on the
// objective (when the start is eligible).
#pragma once

#include <functional>
#include <optional>

#include "penumbra/tune/search_space.h"

namespace penumbra::tune {

struct Trial {
  double objective = 0.0;  // lower is better
  // False: outside a budget or refused by the renderer; never returned, and the optimiser sees
  // a penalty instead of its objective.
  bool eligible = true;
  // Refused as too slow to measure: when the search reached it by changing one discrete
  // dimension, it does not try that value again in later rounds (its cost is that value's).
  bool tooSlow = false;
};

// Evaluates one point (called once per distinct point: the search remembers what it has seen).
using Objective = std::function<Trial(const Point& point)>;

struct SearchLimits {
  int maxEvaluations = 60;  // distinct points evaluated, the start included
  int maxRounds = 3;
  double unitTolerance = 1e-3;  // NLopt's stop on the step in the unit cube
};

struct SearchResult {
  std::optional<Point> best;  // none when no eligible point was seen
  double bestObjective = 0.0;
  int evaluations = 0;
  int rounds = 0;
};

SearchResult searchBest(const SearchSpace& space, const Point& start, const Objective& objective,
                        const SearchLimits& limits = {});

}  // namespace penumbra::tune
