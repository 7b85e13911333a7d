// Under the cursor: the pixel's receiver depth, the depth distribution its filter region holds
// (the filtered reference's kernel, penumbra/compare/reference_region.h) and every technique's
// shadow test over receiver depth for that distribution (penumbra/curves.h): the papers' curve
// figures, live, for the pixel pointed at.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "penumbra/curves.h"
#include "penumbra/gl/renderer.h"

namespace penumbra::viewer {

struct CursorProbe {
  int x = 0, y = 0;  // frame pixel, row 0 at the top
  int cascade = 0;
  float receiverDepth = 0.0f;  // linear light-space depth in [0,1]
  float visibility = 0.0f;     // the shown technique's, as rendered
  std::vector<DepthSample> region;
  CurvesTable curves;  // "exact", then every technique
  std::string status;  // why there is no region (outside the map, facing away); empty otherwise
};

// The probe at pixel (x, y) of `result`; `depthMaps` holds each cascade's light-pass depth of that
// render (Renderer::readDepthMap). Throws Error only for parameters the curves refuse.
CursorProbe probePixel(const gl::RenderResult& result, const std::vector<Image>& depthMaps, int x,
                       int y);

// An ImGui window at `position`, `size`: the numbers, the distribution as a histogram and the
// curves, `shown`'s curve and the exact one drawn thick, a marker at the receiver's depth.
// `truthLine` (when not empty): the true shadow at the pixel, below the numbers.
void drawCursorProbe(const CursorProbe& probe, Technique shown, float positionX, float positionY,
                     float width, float height, const std::string& truthLine = {});

}  // namespace penumbra::viewer
