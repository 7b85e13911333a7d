// Gumbau et al. Fig. 3: the power-function CDF against VSM and ESM on the spheres scene, and
// where the power CDF's leaking pixels are, to say why it leaks.
#include "figure_gumbau.h"

#include <algorithm>
#include <cmath>

#include "penumbra/compare/html_text.h"
#include "penumbra/metrics.h"
#include "penumbra/scene.h"
#include "render_figure_tools.h"

namespace penumbra::compare {
namespace {

// Where the power CDF's leaking pixels are, to say why it leaks (spheres scene). A pixel leaks
// where its error exceeds the comparison's tau, as the table's counts take it.
struct LeakAnatomy {
  int leaks = 0;      // the power CDF's leaking pixels
  int sharedVsm = 0;  // of them, also leaking with VSM
  int fullyLit = 0;   // of them, reading 1: the receiver at or in front of the filtered mean
  int ownSlope = 0;   // of the fully lit, the nearest depth in the kernel within the receiver's
                      // own depth change across it: no occluder but its own surface
  double fullyLitGap = 0.0;    // median receiver - nearest depth, world units, of the fully lit
  double partialGap = 0.0;     // the same for the others (leaking, but below 1)
  double partialExcess = 0.0;  // their median visibility - reference
};

LeakAnatomy leakAnatomy(gl::Renderer& renderer, const FiguresOptions& o, const Scene& scene,
                        const TechniqueResult& cdf, const TechniqueResult& vsm, double tau) {
  gl::RenderSettings s = figureSettings(o);
  s.technique = Technique::PowerCdf;
  s.params = cdf.params;
  s.lookupInputs = true;  // each leaking pixel's lookup
  const gl::RenderResult frame = renderer.render(scene, s);
  const Image depth = renderer.readDepthMap();
  const float metres = frame.cascadeFrame.light.farDistance - frame.cascadeFrame.light.nearDistance;
  const int radius = s.blur.radius, size = depth.width();
  LeakAnatomy a;
  std::vector<double> fullGaps, partialGaps, partialExcess;
  for (int y = 0; y < cdf.error.height(); ++y) {
    for (int x = 0; x < cdf.error.width(); ++x) {
      if (cdf.error.at(x, y) <= tau) continue;
      ++a.leaks;
      if (vsm.error.at(x, y) > tau) ++a.sharedVsm;
      const LookupPixel p = gl::lookupPixelAt(frame, x, y);
      const int tx = int(p.uv.x * float(size)), ty = int(p.uv.y * float(size));
      float nearest = 1.0f;  // over the prefilter's (2r+1)^2 texels around the lookup
      for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
          nearest = std::min(nearest, depth.at(std::clamp(tx + dx, 0, size - 1),
                                               std::clamp(ty + dy, 0, size - 1)));
        }
      }
      const float gap = p.receiverDepth - nearest;
      if (cdf.visibility.at(x, y) >= 0.999f) {
        ++a.fullyLit;
        fullGaps.push_back(double(gap * metres));
        const float ownChange = glm::length(p.depthPerTexel) * float(radius) * std::sqrt(2.0f);
        if (gap <= ownChange) ++a.ownSlope;
      } else {
        partialGaps.push_back(double(gap * metres));
        partialExcess.push_back(double(cdf.error.at(x, y)));
      }
    }
  }
  a.fullyLitGap = fullGaps.empty() ? 0.0 : median(fullGaps);
  a.partialGap = partialGaps.empty() ? 0.0 : median(partialGaps);
  a.partialExcess = partialExcess.empty() ? 0.0 : median(partialExcess);
  return a;
}

}  // namespace

FigureItem gumbauFigure3(gl::Renderer& renderer, const FiguresOptions& o,
                         const std::filesystem::path& dir) {
  FigureItem f;
  f.id = "gumbau-fig3";
  f.title = "Gumbau Fig. 3: the power-function CDF against VSM and ESM";
  const std::vector<VariantResult> r = measureVariants(
      renderer, o, f.id, "spheres",
      {{"VSM", Technique::Vsm, {}},
       {"ESM", Technique::Esm, {"classifier=none"}},  // the plain exponential test, as the paper's
       {"power CDF", Technique::PowerCdf, {}}},
      dir, f.images);
  const VisibilityErrors &vsm = r[0].result.filtered, &esm = r[1].result.filtered,
                         &cdf = r[2].result.filtered;
  const double tau = ComparisonRequest{}.tau;
  const LeakAnatomy a =
      leakAnatomy(renderer, o, makeBuiltinScene("spheres"), r[2].result, r[0].result, tau);
  auto share = [&](int part, int whole) {
    return fixedDigits(100.0 * double(part) / double(std::max(whole, 1)), 0) + "%";
  };
  f.paper =
      "On the spheres scene VSM shows overlapping-shadow bleeding and ESM artifacts at contact "
      "points; the power-function CDF eliminates the light bleeding of both (Gumbau et al., "
      "Fig. 3), and renders sharper shadows than the others with the same kernel (§4). Its "
      "visibility is 1 wherever the receiver lies at or in front of the filtered mean depth, by "
      "design: \"unoccluded planar objects are expected to be fully lit\" (§3, eq. 4).";
  f.measured =
      "On the spheres scene against the filtered reference, leaking pixels: VSM " +
      percent(vsm.leakShare) + ", ESM " + percent(esm.leakShare) + ", power CDF " +
      percent(cdf.leakShare) + "; over-darkened: " + percent(vsm.darkShare) + ", " +
      percent(esm.darkShare) + ", " + percent(cdf.darkShare) + ". Of the power CDF's " +
      std::to_string(a.leaks) + " leaking pixels, " + share(a.sharedVsm, a.leaks) +
      " also leak with VSM and " + share(a.fullyLit, a.leaks) +
      " read exactly lit (receiver at or in front of the filtered mean). Those lie a median " +
      fixedDigits(a.fullyLitGap, 3) + " world units behind the nearest depth in the prefilter's " +
      "kernel, and for " + share(a.ownSlope, a.fullyLit) +
      " of them that depth is within the receiver's own depth change across the kernel "
      "(its slope times the kernel's half-diagonal): nothing in the kernel lies in front of the "
      "receiver's plane by more than its slope explains. The remaining " +
      std::to_string(a.leaks - a.fullyLit) + " lie a median " + fixedDigits(a.partialGap, 2) +
      " world units behind the nearest depth in the kernel and read " +
      fixedDigits(a.partialExcess, 2) + " above the reference (median), below 1.";
  f.agrees = cdf.leakShare < vsm.leakShare && cdf.leakShare < esm.leakShare;
  const bool ownSurfaceCause =
      2 * a.fullyLit > a.leaks && 2 * a.sharedVsm > a.leaks && 2 * a.ownSlope > a.fullyLit;
  std::string leaksMoreThan;  // the techniques the power CDF does not beat
  for (const VariantResult& v : {r[0], r[1]}) {
    if (cdf.leakShare >= v.result.filtered.leakShare) {
      leaksMoreThan += (leaksMoreThan.empty() ? "" : " and ") + v.variant.label;
    }
  }
  f.verdict =
      f.agrees ? "the power CDF leaks on fewer pixels than both."
      : ownSurfaceCause
          ? "the power CDF leaks on as many pixels as " + leaksMoreThan + " or more here, but " +
                share(a.sharedVsm, a.leaks) + " of its leaks are VSM's own pixels and " +
                share(a.fullyLit, a.leaks) + " read exactly 1, most of those (" +
                share(a.ownSlope, a.fullyLit) +
                ") with nothing in the kernel in front of the receiver's plane beyond its own "
                "slope. There the filtered mean is at or behind the receiver, and eq. 4 and "
                "Chebyshev's bound both return 1 by construction (the planar-receiver "
                "assumption both methods share, Gumbau §3: planar receivers at the mean are "
                "lit). The paper judges by eye the bleeding of overlapping shadows and ESM's "
                "contact artifacts; we count every pixel 0.05 brighter than the filtered "
                "reference, curved receivers included. The " +
                std::to_string(a.leaks - a.fullyLit) + " partial leaks are not isolated further."
          : "the power CDF leaks on as many pixels as " + leaksMoreThan +
                " or more here, and most of its leaks are neither VSM's nor at a fully lit "
                "receiver: the cause is not isolated.";
  f.tableHtml = errorsTable(r);
  return f;
}

}  // namespace penumbra::compare
