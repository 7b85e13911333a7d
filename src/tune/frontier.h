// The quality-cost frontier of tune's evaluations (docs/tune.md): the settings no other beats in
// both error and cost, which name the best technique for each budget.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::tune {

struct CostPoint {
  std::string technique;
  int evaluation = 0;  // index in its unit's evaluations
  double cost = 0.0;   // ms or MiB
  double error = 0.0;
};

// The points on the frontier, by ascending cost: each has a lower error than every cheaper one
// (ties in cost: the lower error).
std::vector<CostPoint> paretoFront(std::vector<CostPoint> points);

// Every point coloured by technique, the frontier as a line with its points labelled; both
// axes logarithmic (errors must be positive).
void plotFrontier(const std::vector<CostPoint>& points, const std::vector<std::string>& techniques,
                  const std::string& costLabel, const std::string& errorLabel,
                  const std::string& title, const std::filesystem::path& png);

}  // namespace penumbra::tune
