// What the filtered reference filters at one pixel, as the depth distribution the papers' curve
// figures plot (penumbra/curves.h): the report's worst pixel and the viewer's pixel under the
// cursor.
#pragma once

#include <vector>

#include "penumbra/depth_distribution.h"
#include "penumbra/filters.h"
#include "penumbra/image.h"

namespace penumbra::compare {

// Pixel (x, y)'s reference kernel (level-0 taps: bilinear x `blur`) over `depth` (the pixel's
// cascade's light-pass depth, row 0 at the bottom), each tap's depth moved along the receiver
// plane into the receiver's frame. `lookup` and `plane` are RenderResult::lookup and
// ::receiverPlane. The weights sum to 1 (bilinear weights times the normalised blur weights).
std::vector<DepthSample> referenceRegion(const Image& depth, const Image& lookup,
                                         const Image& plane, int x, int y, const BlurSpec& blur);

}  // namespace penumbra::compare
