#include "render_figure_tools.h"

#include <array>
#include <cctype>

#include "penumbra/compare/html_text.h"
#include "penumbra/image_io.h"
#include "penumbra/params.h"
#include "penumbra/compare/report_plots.h"

namespace penumbra::compare {
namespace {

std::string fileName(const std::string& label) {
  std::string out;
  for (char c : label)
    out += std::isalnum(static_cast<unsigned char>(c)) ? char(std::tolower(c)) : '_';
  return out;
}

}  // namespace

gl::RenderSettings figureSettings(const FiguresOptions& o) {
  gl::RenderSettings s;
  s.shadowMapSize = o.shadowMapSize;
  s.width = o.width;
  s.height = o.height;
  return s;
}

std::vector<VariantResult> measureVariants(gl::Renderer& renderer, const FiguresOptions& o,
                                           const std::string& figure, const std::string& scene,
                                           const std::vector<Variant>& variants,
                                           const std::filesystem::path& dir,
                                           std::vector<std::string>& images) {
  std::vector<VariantResult> out;
  for (const Variant& v : variants) {
    ComparisonRequest request;
    request.scene = scene;
    request.techniques = {v.technique};
    request.settings = figureSettings(o);
    const std::array<Technique, 1> one{v.technique};
    for (const char* p : v.params) applyParamAssignment(one, request.settings.params, p);
    request.supersample = 1;
    request.pathFrames = 2;
    request.truth = TruthKind::None;  // the figures plot errors against the filtered reference
    const ComparisonResult r = runComparison(request, renderer);
    const TechniqueResult& t = r.techniques.at(0);
    const std::string base = figure + "_" + fileName(v.label);
    writeColorPng(t.color, dir / "renders" / (base + ".png"));
    plotErrorHeatMap(t.error, 0.5, v.label + ": visibility - filtered reference",
                     dir / "renders" / (base + "_error.png"));
    images.push_back("renders/" + base + ".png");
    images.push_back("renders/" + base + "_error.png");
    out.push_back({v, t});
  }
  return out;
}

std::string errorsTable(const std::vector<VariantResult>& results) {
  std::string t =
      "<table><tr><th>variant</th><th>RMSE</th><th>leaking pixels</th><th>over-darkened "
      "pixels</th><th>max |error|</th></tr>";
  for (const VariantResult& r : results) {
    const VisibilityErrors& e = r.result.filtered;
    t += "<tr><td>" + r.variant.label + "</td><td>" + fixedDigits(e.rmse, 4) + "</td><td>" +
         fixedDigits(100.0 * e.leakShare, 2) + "%</td><td>" + fixedDigits(100.0 * e.darkShare, 2) +
         "%</td><td>" + fixedDigits(e.maxAbsolute) + "</td></tr>";
  }
  return t + "</table>";
}

std::string percent(double share) {
  return fixedDigits(100.0 * share, 2) + "%";
}

}  // namespace penumbra::compare
