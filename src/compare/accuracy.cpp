// The accuracy gate's matrix and configurations, its ceilings table and the check.
#include "penumbra/compare/accuracy.h"

#include <fstream>
#include <iomanip>
#include <sstream>

#include "penumbra/error.h"
#include "penumbra/gl/renderer.h"

namespace penumbra::compare {

ComparisonRequest accuracyRequest(std::string_view scene) {
  ComparisonRequest r;
  r.scene = std::string(scene);
  r.techniques.assign(allTechniques().begin(), allTechniques().end());
  r.settings.shadowMapSize = 256;
  r.settings.blur = {BlurKernel::Box, 2, 1.0f};
  r.settings.filter = FilterMode::Bilinear;
  r.settings.width = 160;
  r.settings.height = 90;
  r.supersample = 1;
  r.pathFrames = 2;
  // The gate holds each technique to its ceilings against the filtered reference, which is
  // what its approximation of the step is measured by (docs/results/accuracy.md).
  r.truth = TruthKind::None;
  return r;
}

std::vector<AccuracyConfiguration> accuracyConfigurations() {
  // Each extra row on a scene where its setting matters: minification's far posts for the mip
  // chain and footprints, backyard's soft penumbrae for the blur kernel, street's depth range for
  // cascades, contact's silhouettes for MSAA.
  return {{"default", ""},         {"trilinear", "minification"}, {"anisotropic", "minification"},
          {"sat", "minification"}, {"gaussian", "backyard"},      {"cascades", "street"},
          {"msaa", "contact"}};
}

ComparisonRequest accuracyRequest(const AccuracyConfiguration& configuration,
                                  std::string_view scene, const gl::Renderer& renderer) {
  ComparisonRequest r = accuracyRequest(scene);
  gl::RenderSettings& s = r.settings;
  if (configuration.name == "trilinear") s.filter = FilterMode::Trilinear;
  if (configuration.name == "anisotropic") s.filter = FilterMode::Anisotropic;
  if (configuration.name == "sat") s.filter = FilterMode::SummedArea;
  if (configuration.name == "gaussian") s.blur = {BlurKernel::Gaussian, 2, 1.0f};
  if (configuration.name == "cascades") s.cascades.count = 3;
  if (configuration.name == "msaa") s.msaaSamples = 4;
  std::vector<Technique> accepted;
  for (Technique t : r.techniques) {
    gl::RenderSettings one = s;
    one.technique = t;
    try {
      renderer.validate(one);
      accepted.push_back(t);
    } catch (const Error&) {
      // e.g. the summed-area filter with exponential channels
    }
  }
  r.techniques = accepted;
  return r;
}

std::vector<AccuracyEntry> measureAccuracy(gl::Renderer& renderer, const Progress& progress) {
  struct Run {
    AccuracyConfiguration configuration;
    std::string scene;
  };
  std::vector<Run> runs;
  for (const AccuracyConfiguration& c : accuracyConfigurations()) {
    if (!c.scene.empty()) {
      runs.push_back({c, c.scene});
      continue;
    }
    for (std::string_view scene : builtinSceneNames()) runs.push_back({c, std::string(scene)});
  }
  std::vector<AccuracyEntry> entries;
  for (size_t i = 0; i < runs.size(); ++i) {
    const Run& run = runs[i];
    if (progress) {
      progress(int(i), int(runs.size()), run.configuration.name + " " + run.scene);
    }
    const ComparisonResult result =
        runComparison(accuracyRequest(run.configuration, run.scene, renderer), renderer);
    for (const TechniqueResult& t : result.techniques) {
      entries.push_back({run.configuration.name, run.scene, std::string(techniqueId(t.technique)),
                         t.filtered.rmse});
    }
  }
  if (progress) progress(int(runs.size()), int(runs.size()), "measured");
  return entries;
}

std::vector<AccuracyCeiling> readAccuracyCeilings(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  if (!in) throw Error("cannot read the accuracy ceilings " + csv.string());
  std::vector<AccuracyCeiling> ceilings;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#' || line.rfind("configuration,", 0) == 0) continue;
    std::istringstream row(line);
    AccuracyCeiling c;
    std::string measured, ceiling, extra;
    std::getline(row, c.configuration, ',');
    std::getline(row, c.scene, ',');
    std::getline(row, c.technique, ',');
    std::getline(row, measured, ',');
    std::getline(row, ceiling, ',');
    const bool extraColumn = bool(std::getline(row, extra, ','));
    try {
      size_t usedMeasured = 0, usedCeiling = 0;
      c.measured = std::stod(measured, &usedMeasured);
      c.ceiling = std::stod(ceiling, &usedCeiling);
      if (extraColumn || usedMeasured != measured.size() || usedCeiling != ceiling.size() ||
          !(c.ceiling >= 0.0)) {
        throw std::invalid_argument(ceiling);
      }
    } catch (const std::exception&) {
      throw Error(csv.string() + ":" + std::to_string(number) +
                  ": expected configuration,scene,technique,measured_rmse,ceiling_rmse with "
                  "numbers, got '" +
                  line + "'");
    }
    for (const AccuracyCeiling& earlier : ceilings) {
      if (earlier.configuration == c.configuration && earlier.scene == c.scene &&
          earlier.technique == c.technique) {
        throw Error(csv.string() + ":" + std::to_string(number) + ": a second ceiling for " +
                    c.configuration + " " + c.scene + " " + c.technique);
      }
    }
    ceilings.push_back(c);
  }
  return ceilings;
}

std::vector<AccuracyCeiling> ceilingsFor(const std::vector<AccuracyEntry>& measured, double factor,
                                         double floor) {
  std::vector<AccuracyCeiling> ceilings;
  for (const AccuracyEntry& e : measured) {
    ceilings.push_back(
        {e.configuration, e.scene, e.technique, e.rmse, std::max(factor * e.rmse, floor)});
  }
  return ceilings;
}

void writeAccuracyCeilings(const std::vector<AccuracyCeiling>& ceilings,
                           const std::filesystem::path& csv) {
  std::ofstream out(csv);
  out << "configuration,scene,technique,measured_rmse,ceiling_rmse\n" << std::setprecision(4);
  for (const AccuracyCeiling& c : ceilings) {
    out << c.configuration << "," << c.scene << "," << c.technique << "," << c.measured << ","
        << c.ceiling << "\n";
  }
  if (!out) throw Error("cannot write the accuracy ceilings " + csv.string());
}

std::vector<std::string> checkAccuracy(const std::vector<AccuracyEntry>& measured,
                                       const std::vector<AccuracyCeiling>& ceilings) {
  std::vector<std::string> problems;
  auto find = [&](const AccuracyEntry& e) {
    for (const AccuracyCeiling& c : ceilings) {
      if (c.configuration == e.configuration && c.scene == e.scene && c.technique == e.technique)
        return &c;
    }
    return static_cast<const AccuracyCeiling*>(nullptr);
  };
  for (const AccuracyEntry& e : measured) {
    const AccuracyCeiling* c = find(e);
    std::ostringstream text;
    text << std::setprecision(4) << e.configuration << " " << e.scene << " " << e.technique
         << ": RMSE " << e.rmse;
    if (c == nullptr) {
      problems.push_back(text.str() + " has no ceiling in the table");
    } else if (!(e.rmse <= c->ceiling)) {
      text << " exceeds its ceiling " << c->ceiling << " (measured " << c->measured
           << " when it was set)";
      problems.push_back(text.str());
    }
  }
  for (const AccuracyCeiling& c : ceilings) {
    bool found = false;
    for (const AccuracyEntry& e : measured)
      found |=
          e.configuration == c.configuration && e.scene == c.scene && e.technique == c.technique;
    if (!found)
      problems.push_back(c.configuration + " " + c.scene + " " + c.technique +
                         ": a ceiling without a measurement");
  }
  return problems;
}

}  // namespace penumbra::compare
