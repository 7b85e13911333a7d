// The mixed discrete/continuous search (search.h) with NLopt for the continuous part.
#include "penumbra/tune/search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <exception>
#include <functional>
#include <map>
#include <nlopt.hpp>
#include <set>
#include <stdexcept>

#include "penumbra/error.h"

namespace penumbra::tune {
namespace {

// What the optimiser sees for an ineligible point: worse than any visibility error (RMSE and
// its weighted forms stay within a few units), finite so BOBYQA's model stays defined.
constexpr double kIneligiblePenalty = 1e3;
// Where the optimiser starts a continuous dimension whose value is "auto": a quarter of the way
// up its scale, the first decade above zero of a ZeroLog range, where the registry's automatic
// floors live (MSM's moment bias: 3e-6 to 3e-5 of [0, 0.01]).
constexpr double kAutoStartUnit = 0.25;
// NLopt's first step in the unit cube: a tenth of each range, coarse enough to leave a flat
// start (a bias of zero) and fine enough not to jump past a minimum near a bound.
constexpr double kInitialUnitStep = 0.1;
// NLopt calls per new point allowed: it revisits points (free, remembered) as it shrinks its
// steps.
constexpr int kMaxCallsPerNewPoint = 4;

class Search {
 public:
  Search(const SearchSpace& space, const Objective& objective, const SearchLimits& limits)
      : space_(space), objective_(objective), limits_(limits), roundCap_(limits.maxEvaluations) {}

  bool exhausted() const { return evaluations_ >= roundCap_; }

  // The objective of a point (infinity when ineligible or beyond the evaluation cap and unseen).
  double value(const Point& p) {
    const auto seen = seen_.find(p);
    if (seen != seen_.end()) return seen->second;
    if (exhausted()) return std::numeric_limits<double>::infinity();
    const Trial t = objective_(p);
    ++evaluations_;
    lastTooSlow_ = t.tooSlow;
    const double v =
        t.eligible && std::isfinite(t.objective) ? t.objective : std::numeric_limits<double>::infinity();
    seen_.emplace(p, v);
    if (std::isfinite(v) && (!best_ || v < bestValue_)) {
      best_ = p;
      bestValue_ = v;
    }
    return v;
  }

  // Walks one discrete dimension from `current`; returns the point with its best value.
  Point walkDiscrete(Point current, size_t dim) {
    const Dimension& d = space_.dimensions[dim];
    double currentValue = value(current);
    if (d.ordinal) {
      const auto at = std::find(d.values.begin(), d.values.end(), current[dim]);
      const long start = at == d.values.end() ? 0 : long(at - d.values.begin());
      for (const long direction : {1L, -1L}) {
        bool moved = false;
        for (long i = start + direction; i >= 0 && i < long(d.values.size()); i += direction) {
          Point candidate = current;
          candidate[dim] = d.values[size_t(i)];
          const double v = value(candidate);
          if (!(v < currentValue)) break;  // the line stops improving
          current = candidate;
          currentValue = v;
          moved = true;
        }
        // Improving upward means the way down, from the start, has already been left behind.
        if (moved) break;
      }
      return current;
    }
    Point best = current;
    for (const std::string& option : d.values) {
      if (option == current[dim] || tooSlow_.count({dim, option})) continue;
      Point candidate = current;
      candidate[dim] = option;
      lastTooSlow_ = false;
      const double v = value(candidate);
      if (lastTooSlow_) tooSlow_.insert({dim, option});
      if (v < currentValue) {
        best = candidate;
        currentValue = v;
      }
    }
    return best;
  }

  // NLopt over the continuous dimensions from `current`, with at most `evaluations` new points.
  Point optimiseContinuous(const Point& current, int evaluations) {
    std::vector<size_t> dims;
    for (size_t i = 0; i < space_.dimensions.size(); ++i) {
      if (space_.dimensions[i].continuous) dims.push_back(i);
    }
    if (dims.empty() || evaluations <= 0) return current;
    std::vector<double> x;
    for (size_t i : dims) {
      x.push_back(current[i] == "auto" ? kAutoStartUnit
                                       : unitOf(space_.dimensions[i], std::stod(current[i])));
    }
    const auto pointAt = [&](const std::vector<double>& u) {
      Point p = current;
      for (size_t k = 0; k < dims.size(); ++k) {
        p[dims[k]] = continuousText(valueAt(space_.dimensions[dims[k]], u[k]));
      }
      return p;
    };
    // NLopt's C++ wrapper replaces an exception thrown by the objective with its own (losing
    // the message), so the objective's are kept here and rethrown after it stops.
    struct Context {
      Search* search;
      std::function<Point(const std::vector<double>&)> at;
      std::exception_ptr failure;
    } context{this, pointAt, nullptr};
    const auto f = [](const std::vector<double>& u, std::vector<double>&, void* data) {
      auto* c = static_cast<Context*>(data);
      if (c->failure || c->search->exhausted()) throw nlopt::forced_stop();
      try {
        const double v = c->search->value(c->at(u));
        return std::isfinite(v) ? v : kIneligiblePenalty;
      } catch (...) {
        c->failure = std::current_exception();
        throw nlopt::forced_stop();
      }
    };
    // BOBYQA models the objective quadratically (it needs two dimensions or more); Sbplx,
    // Nelder-Mead on subspaces, takes one.
    nlopt::opt opt(dims.size() >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_SBPLX, unsigned(dims.size()));
    opt.set_lower_bounds(std::vector<double>(dims.size(), 0.0));
    opt.set_upper_bounds(std::vector<double>(dims.size(), 1.0));
    opt.set_initial_step(std::vector<double>(dims.size(), kInitialUnitStep));
    opt.set_xtol_abs(limits_.unitTolerance);
    // NLopt counts every call, points seen before included (they cost nothing); the cap on new
    // points is the round's share, enforced here by stopping the optimiser.
    opt.set_maxeval(kMaxCallsPerNewPoint * evaluations);
    roundCap_ = std::min(limits_.maxEvaluations, evaluations_ + evaluations);
    opt.set_min_objective(f, &context);
    double found = 0.0;
    try {
      opt.optimize(x, found);
    } catch (const nlopt::forced_stop&) {
      // The round's share is spent.
    } catch (const nlopt::roundoff_limited&) {
      // Converged as far as floating point allows: the best point is kept below.
    } catch (const std::exception& e) {
      roundCap_ = limits_.maxEvaluations;
      if (context.failure) std::rethrow_exception(context.failure);
      throw Error(std::string("tune: NLopt failed: ") + e.what());
    }
    roundCap_ = limits_.maxEvaluations;
    if (context.failure) std::rethrow_exception(context.failure);
    return best_ ? *best_ : current;
  }

  int evaluations() const { return evaluations_; }
  const std::optional<Point>& best() const { return best_; }
  double bestValue() const { return bestValue_; }

 private:
  const SearchSpace& space_;
  const Objective& objective_;
  SearchLimits limits_;
  int roundCap_;  // evaluations allowed until the current NLopt run stops
  std::map<Point, double> seen_;
  std::set<std::pair<size_t, std::string>> tooSlow_;  // categorical values not to try again
  bool lastTooSlow_ = false;
  int evaluations_ = 0;
  std::optional<Point> best_;
  double bestValue_ = std::numeric_limits<double>::infinity();
};

}  // namespace

SearchResult searchBest(const SearchSpace& space, const Point& start, const Objective& objective,
                        const SearchLimits& limits) {
  if (start.size() != space.dimensions.size()) {
    throw Error("tune: the start has " + std::to_string(start.size()) + " values for " +
                std::to_string(space.dimensions.size()) + " dimensions");
  }
  if (limits.maxEvaluations < 1) throw Error("tune: at least one evaluation is needed");
  Search search(space, objective, limits);
  search.value(start);  // the user's setting, always measured
  Point current = start;
  SearchResult result;
  for (int round = 0; round < limits.maxRounds && !search.exhausted(); ++round) {
    ++result.rounds;
    const double before = search.bestValue();
    for (size_t i = 0; i < space.dimensions.size() && !search.exhausted(); ++i) {
      if (!space.dimensions[i].continuous) current = search.walkDiscrete(current, i);
    }
    // Continue from the best point seen (an ineligible start is left behind).
    if (search.best()) current = *search.best();
    // The continuous part's share: the rest of this round's part of what remains.
    const int remaining = limits.maxEvaluations - search.evaluations();
    // At least what BOBYQA needs to build its model (2n + 1 points) and take two steps from it.
    const int continuous = int(std::count_if(space.dimensions.begin(), space.dimensions.end(),
                                             [](const Dimension& d) { return d.continuous; }));
    const int share = std::min(
        remaining, std::max(2 * continuous + 3, remaining / std::max(1, limits.maxRounds - round)));
    current = search.optimiseContinuous(current, share);
    if (!(search.bestValue() < before)) break;  // a round without progress ends the search
  }
  result.best = search.best();
  result.bestObjective = search.bestValue();
  result.evaluations = search.evaluations();
  return result;
}

}  // namespace penumbra::tune
