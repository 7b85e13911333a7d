// --technique and --param handling.
#include "technique_options.h"

#include <iostream>

#include "penumbra/params.h"

namespace penumbra::cli {

void addTechniqueOptions(CLI::App& app, TechniqueOptions& options) {
  app.add_option("-t,--technique", options.techniques,
                 "technique ids, comma-separated, or 'all'; 'list' prints them with their "
                 "parameters")
      ->capture_default_str();
  app.add_option("-p,--param", options.params,
                 "NAME=VALUE or TECHNIQUE.NAME=VALUE, repeatable (see --technique list)");
}

bool printTechniqueListIfAsked(const TechniqueOptions& options) {
  if (options.techniques != "list") return false;
  for (Technique t : allTechniques()) {
    std::cout << techniqueId(t) << "  " << techniqueTitle(t) << "\n" << describeParams(t) << "\n";
  }
  return true;
}

std::vector<Technique> selectedTechniques(const TechniqueOptions& options) {
  if (options.techniques == "all") {
    return {allTechniques().begin(), allTechniques().end()};
  }
  std::vector<Technique> selected;
  std::string_view text = options.techniques;
  while (true) {
    size_t comma = text.find(',');
    selected.push_back(parseTechnique(text.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return selected;
}

TechniqueParams selectedParams(const TechniqueOptions& options,
                               const std::vector<Technique>& techniques) {
  TechniqueParams params = defaultTechniqueParams();
  for (const std::string& assignment : options.params) {
    applyParamAssignment(techniques, params, assignment);
  }
  for (Technique t : techniques) validateParams(t, params);
  return params;
}

}  // namespace penumbra::cli
