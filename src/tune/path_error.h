// tune's objectives (tune.h ErrorMeasure) over frames of the camera path: a setting's
// visibility against each frame's target, pooled over the frames' measured pixels.
#pragma once

#include <cstddef>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/tune/tune.h"

namespace penumbra::tune {

// One frame's target and the pixels measured against it (mask > 0.5).
struct FrameTarget {
  Image visibility;
  Image mask;
};

// The frame size of a search or a confirmation, and its targets.
struct PathTargets {
  int width = 0;
  int height = 0;
  std::vector<FrameTarget> frames;
};

struct SetError {
  double measure = 0.0;  // the request's ErrorMeasure
  double rmse = 0.0;
};

// The measure over frames [first, last): RMSE pooled over their pixels; leak-weighted, each
// squared error of a pixel lighter than its target (visibility - target > 0: light leaking)
// counted leakWeight times; flicker, RMSE plus temporalFlicker against the targets.
SetError errorOver(ErrorMeasure measure, double leakWeight, const std::vector<Image>& visibility,
                   const PathTargets& targets, size_t first, size_t last);

}  // namespace penumbra::tune
