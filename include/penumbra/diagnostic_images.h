// Colour images that explain a render: the signed-error heat map of the comparison report, the
// ESM failure mask and LVSM's layer colours. The report, `penumbra render` and the viewer all
// colour through here, so a colour means the same everywhere.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>

#include "penumbra/image.h"

namespace penumbra {

// The diverging palette of signed visibility error (ColorBrewer RdBu): blue where a technique
// over-darkens (error -range), white where it is exact, red where it leaks light (+range).
struct ErrorPaletteStop {
  float position;            // error / range, in [-1, 1]
  uint8_t red, green, blue;  // sRGB-encoded
};
std::span<const ErrorPaletteStop> errorPalette();
// The palette at `error` (clamped to [-range, range]), interpolated between stops in sRGB as
// gnuplot does: sRGB-encoded RGB in [0,1].
glm::vec3 errorHeatColour(float error, float range);

// Linear RGB, row 0 at the top (RenderResult::diagnostic, -1 where nothing is drawn, and the
// shaded colour): failing pixels red over grey shading; and layer indices in distinct colours
// (thesis Fig. 4.2), shaded by the colour's green channel.
Image failureMaskImage(const Image& diagnostic, const Image& color);
Image layerIndexImage(const Image& diagnostic, const Image& color);

}  // namespace penumbra
