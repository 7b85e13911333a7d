// The probe and its plot.
#include "cursor_probe.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "penumbra/compare/reference_region.h"

namespace penumbra::viewer {
namespace {

constexpr int kCurveSamples = 2001;  // receiver depths over [0,1]: 0.0005 apart
constexpr int kHistogramBins = 48;

ImU32 curveColour(size_t column, size_t columns) {
  if (column == 0) return IM_COL32(255, 255, 255, 255);  // exact
  // Hues spread around the wheel, one per technique.
  float r = 0.0f, g = 0.0f, b = 0.0f;
  ImGui::ColorConvertHSVtoRGB(float(column - 1) / float(std::max<size_t>(columns - 1, 1)), 0.65f,
                              1.0f, r, g, b);
  return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, 1.0f));
}

}  // namespace

CursorProbe probePixel(const gl::RenderResult& result, const std::vector<Image>& depthMaps, int x,
                       int y) {
  CursorProbe probe;
  probe.x = x;
  probe.y = y;
  probe.receiverDepth = result.lookup.at(x, y, 2);
  probe.visibility = result.visibility.at(x, y);
  probe.cascade = int(result.cascades.at(x, y, 0));
  if (result.diagnostic.at(x, y) < 0.0f) {
    probe.status = "nothing drawn here";
  } else if (probe.cascade < 0 || result.lookup.at(x, y, 3) < 0.25f) {
    probe.status = "outside the shadow map";
  } else if (result.lookup.at(x, y, 3) < 0.75f) {
    probe.status = "facing away from the light: the shadow test does not decide the shading";
  }
  if (!probe.status.empty() || size_t(probe.cascade) >= depthMaps.size()) return probe;
  const size_t cascade = size_t(probe.cascade);
  probe.region = compare::referenceRegion(depthMaps[cascade], result.lookup, result.receiverPlane,
                                          x, y, result.cascadeBlurs[cascade]);
  CurvesRequest request;
  request.occluders = probe.region;
  request.techniques.assign(allTechniques().begin(), allTechniques().end());
  request.params = result.params;
  request.samples = kCurveSamples;
  probe.curves = computeCurves(request);
  return probe;
}

void drawCursorProbe(const CursorProbe& probe, Technique shown, float positionX, float positionY,
                     float width, float height, const std::string& truthLine) {
  ImGui::SetNextWindowPos(ImVec2(positionX, positionY));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  ImGui::Begin("under the cursor", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::Text("pixel (%d, %d)  cascade %d  receiver depth %.5f  visibility %.3f", probe.x, probe.y,
              probe.cascade, double(probe.receiverDepth), double(probe.visibility));
  if (!truthLine.empty()) ImGui::TextUnformatted(truthLine.c_str());
  if (!probe.status.empty() || probe.curves.columns.empty()) {
    ImGui::TextDisabled("%s", probe.status.c_str());
    ImGui::End();
    return;
  }
  // The depth range the region and the receiver span, with a margin: the papers' figures zoom
  // the same way, the whole [0,1] would squeeze every transition into a step.
  float lo = probe.receiverDepth, hi = probe.receiverDepth;
  for (const DepthSample& s : probe.region) lo = std::min(lo, s.depth), hi = std::max(hi, s.depth);
  const float margin = std::max(0.25f * (hi - lo), 0.01f);
  lo = std::max(0.0f, lo - margin);
  hi = std::min(1.0f, hi + margin);

  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float legendWidth = 110.0f;
  const ImVec2 size(std::max(50.0f, ImGui::GetContentRegionAvail().x - legendWidth),
                    std::max(50.0f, ImGui::GetContentRegionAvail().y - 18.0f));
  const auto toScreen = [&](float depth, float value) {
    return ImVec2(origin.x + (depth - lo) / (hi - lo) * size.x, origin.y + (1.0f - value) * size.y);
  };
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                      IM_COL32(25, 25, 30, 255));
  // The distribution: each bin's share of the filter region.
  std::vector<float> bins(kHistogramBins, 0.0f);
  for (const DepthSample& s : probe.region) {
    const int bin =
        std::clamp(int((s.depth - lo) / (hi - lo) * kHistogramBins), 0, kHistogramBins - 1);
    bins[size_t(bin)] += s.weight;
  }
  for (int b = 0; b < kHistogramBins; ++b) {
    if (bins[size_t(b)] <= 0.0f) continue;
    const float x0 = lo + (hi - lo) * float(b) / kHistogramBins;
    const float x1 = lo + (hi - lo) * float(b + 1) / kHistogramBins;
    draw->AddRectFilled(toScreen(x0, std::min(bins[size_t(b)], 1.0f)), toScreen(x1, 0.0f),
                        IM_COL32(90, 90, 110, 255));
  }
  // The curves.
  const CurvesTable& t = probe.curves;
  for (size_t c = 0; c < t.columns.size(); ++c) {
    const bool thick = c == 0 || t.columns[c] == techniqueId(shown);
    std::vector<ImVec2> points;
    for (size_t i = 0; i < t.receiverDepths.size(); ++i) {
      const float z = t.receiverDepths[i];
      if (z < lo || z > hi) continue;
      points.push_back(toScreen(z, std::clamp(t.values[c][i], 0.0f, 1.0f)));
    }
    if (points.size() >= 2) {
      draw->AddPolyline(points.data(), int(points.size()), curveColour(c, t.columns.size()), 0,
                        thick ? 3.0f : 1.2f);
    }
  }
  // The receiver, with a marker above the plot (the exact step coincides with its line).
  const ImVec2 top = toScreen(probe.receiverDepth, 1.0f);
  draw->AddLine(top, toScreen(probe.receiverDepth, 0.0f), IM_COL32(255, 160, 0, 255), 1.5f);
  draw->AddTriangleFilled(ImVec2(top.x - 6.0f, top.y), ImVec2(top.x + 6.0f, top.y),
                          ImVec2(top.x, top.y + 9.0f), IM_COL32(255, 160, 0, 255));
  // Legend.
  for (size_t c = 0; c < t.columns.size(); ++c) {
    const ImVec2 at(origin.x + size.x + 10.0f, origin.y + 16.0f * float(c));
    draw->AddRectFilled(at, ImVec2(at.x + 12.0f, at.y + 10.0f), curveColour(c, t.columns.size()));
    draw->AddText(ImVec2(at.x + 16.0f, at.y - 3.0f), IM_COL32(220, 220, 220, 255),
                  t.columns[c].c_str());
  }
  ImGui::Dummy(size);
  ImGui::Text(
      "visibility over receiver depth %.4f .. %.4f; bars: the region's depths (%zu taps), "
      "orange: this receiver",
      double(lo), double(hi), probe.region.size());
  ImGui::End();
}

}  // namespace penumbra::viewer
