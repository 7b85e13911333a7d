// A frame that is mostly in shadow for every technique says more about the view than about the
// techniques: a sky dome or a room enclosing the scene, a light outside the geometry that holds
// it. render and compare warn and name the likely cause instead of ranking such a frame silently.
#pragma once

#include <optional>
#include <string>

#include "penumbra/image.h"
#include "penumbra/scene.h"

namespace penumbra::compare {

// More than this share of the lit surfaces in shadow (visibility below 0.5) is "mostly".
inline constexpr double kMostlyShadowedShare = 0.8;

// The share of the pixels whose shading the shadow test decides (`coverage` > 0.5:
// litSurfaceMask, surfaces facing the light inside its map) with visibility below 0.5; 0 where
// there are none.
double shadowedShare(const Image& visibility, const Image& coverage);

// The warning for a frame whose every technique (and reference) has `share` of its pixels in
// shadow, share > kMostlyShadowedShare, with the likely cause for this scene's light and camera;
// nothing below that. A sentence for a report; front ends prefix "warning: ".
std::optional<std::string> mostlyShadowedWarning(const Scene& scene, double share);

}  // namespace penumbra::compare
