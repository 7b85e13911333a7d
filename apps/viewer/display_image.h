// What the scene area shows: the render, or one of its diagnostics, as 8-bit sRGB pixels. Colours
// come from the library (the report's heat map, the render command's failure mask and layer
// colours); the viewer only picks which.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/gl/renderer.h"
#include "penumbra/metrics.h"
#include "penumbra/truth/true_shadow.h"

namespace penumbra::viewer {

enum class View {
  Shaded,       // the shaded colour (with the renderer's cascade tint when that overlay is on)
  Visibility,   // the technique's visibility, grey
  Error,        // visibility minus the filtered reference: the report's diverging heat map
  TrueError,    // visibility minus the ray-traced true shadow: the same heat map, silhouettes marked
  FailureMask,  // ESM with a classifier: failing pixels red
  Layers,       // LVSM: each receiver's layer in its colour
  ShadowMap,    // the light pass's linear depth, cascade 0
  Channel,      // a prefiltered channel (level 0; PCF, hard: their depth), normalised to its range
};
inline constexpr View kViews[] = {View::Shaded,      View::Visibility, View::Error,
                                  View::TrueError,   View::FailureMask, View::Layers,
                                  View::ShadowMap,   View::Channel};
std::string_view viewName(View view);
// Short names for --show: shaded, visibility, error, truth-error, failures, layers, shadowmap,
// channel.
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
// The error-against-the-true-shadow view's pixels that are not measured, in colours the heat
// map's blue-white-red palette has not (sRGB bytes): where the render and the trace see
// different surfaces (silhouettes: truth::matchRasterisedSurfaces), and where the trace hits none.
inline constexpr uint8_t kSilhouetteColour[3] = {0x1b, 0xc4, 0x4a};
inline constexpr uint8_t kNoSurfaceColour[3] = {0x58, 0x58, 0x58};
// Where the light does not reach a sub-pixel's surface as the render lights it
// (TrueShadow::reachedByLight: the shadow terminator, an unlit face, outside a spot's cone) and
// the shadow test decides the render's shading: left out as compare leaves it out.
inline constexpr uint8_t kTerminatorColour[3] = {0xe0, 0xa0, 0x20};

// The ray-traced truth of the render's camera, light and frame size, and where its surfaces are
// the render's: what View::TrueError compares the render with.
struct TrueShadowFrame {
  const truth::TrueShadow& trace;
  const truth::SurfaceMatch& match;
};

// `reference` is the filtered reference's visibility (needed for View::Error only), its first
// `referenceRows` rows computed (negative: all): the rows below show the visibility at half
// brightness until the reference reaches them. `maps` is a single-channel image for ShadowMap
// and Channel, row 0 at the bottom as the renderer reads it.
// `truth` is needed for View::TrueError only: without it, the visibility at half brightness.
DisplayImage composeDisplay(View view, const gl::RenderResult& result, const Image* reference,
                            const Image* map, int referenceRows = -1,
                            const TrueShadowFrame* truth = nullptr);

// Visibility minus reference where the shadow test decides the shading (0 elsewhere), as the
// report measures it (penumbra/metrics.h).
Image visibilityError(const gl::RenderResult& result, const Image& reference);

// The pixels measured against the true shadow: the shadow test decides the shading, the trace
// sees a surface, it is the render's, and its triangle faces the light (as compare measures).
Image trueShadowCoverage(const gl::RenderResult& result, const TrueShadowFrame& truth);
// The render's visibility against the true shadow over trueShadowCoverage (penumbra/metrics.h).
VisibilityErrors measureAgainstTrueShadow(const gl::RenderResult& result,
                                          const TrueShadowFrame& truth);
// The truth at pixel (x, y) for the cursor probe: its visibility and the render's error, or why
// it is not measured there.
std::string describeTrueShadowAt(const gl::RenderResult& result, const TrueShadowFrame& truth,
                                 int x, int y);

}  // namespace penumbra::viewer
