// Crops for scenes without known trouble spots: the regions where the techniques' visibility
// differs most from the filtered reference.
#pragma once

#include <vector>

#include "penumbra/image.h"
#include "penumbra/scene.h"

namespace penumbra::compare {

// Up to `count` non-overlapping windows, each `fraction` of the image's width and height, in
// decreasing order of summed |error| over all the given error images (same size, 1 channel).
// Windows whose error sums to zero are not returned; named "largest error 1", "... 2", ...
std::vector<TroubleSpot> largestErrorRegions(const std::vector<Image>& errors, int count,
                                             float fraction = 0.2f);

}  // namespace penumbra::compare
