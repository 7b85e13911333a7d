// What the scene area shows: the render, or one of its diagnostics, as 8-bit sRGB pixels. Colours
// come from the library (the report's heat map, the render command's failure mask and layer
// colours); the viewer only picks which.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "penumbra/gl/renderer.h"

namespace penumbra::viewer {

enum class View {
  Shaded,       // the shaded colour (with the renderer's cascade tint when that overlay is on)
  Visibility,   // the technique's visibility, grey
  Error,        // visibility minus the filtered reference: the report's diverging heat map
  FailureMask,  // ESM with a classifier: failing pixels red
  Layers,       // LVSM: each receiver's layer in its colour
  ShadowMap,    // the light pass's linear depth, cascade 0
  Channel,      // one of the technique's prefiltered channels (level 0), normalised to its range
};
inline constexpr View kViews[] = {View::Shaded, View::Visibility, View::Error,  View::FailureMask,
                                  View::Layers, View::ShadowMap,  View::Channel};
std::string_view viewName(View view);
// Short names for --show: shaded, visibility, error, failures, layers, shadowmap, channel.
std::string_view viewId(View view);
// Throws Error listing the valid names.
View parseView(std::string_view id);

struct DisplayImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  // width * height * 3, sRGB-encoded, row 0 at the top
};

// The report's heat-map range: errors of +-0.5 visibility saturate.
inline constexpr float kErrorRange = 0.5f;

// `reference` is the filtered reference's visibility (needed for View::Error only), its first
// `referenceRows` rows computed (negative: all): the rows below show the visibility at half
// brightness until the reference reaches them. `maps` is a single-channel image for ShadowMap
// and Channel, row 0 at the bottom as the renderer reads it.
DisplayImage composeDisplay(View view, const gl::RenderResult& result, const Image* reference,
                            const Image* map, int referenceRows = -1);

// Visibility minus reference where the shadow test decides the shading (0 elsewhere), as the
// report measures it (penumbra/metrics.h).
Image visibilityError(const gl::RenderResult& result, const Image& reference);

}  // namespace penumbra::viewer
