// Supersampled frames back to the frame size: the references' sub-pixel average.
#pragma once

#include "penumbra/image.h"

namespace penumbra::gl {

// Box-averages factor x factor blocks (factor 1: the image itself).
Image boxDownsample(const Image& image, int factor);

}  // namespace penumbra::gl
