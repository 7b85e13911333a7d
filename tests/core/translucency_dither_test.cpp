// The light pass's dither for translucent casters (shared/alpha_mask.h): every aligned 4x4 block
// of shadow-map texels holds round(16 alpha) covered texels, each threshold once, so filters of
// four texels or more average it to 1 - alpha.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "penumbra/shared/alpha_mask.h"

namespace penumbra {
namespace {

TEST(TranslucencyDither, EachBlockHoldsEveryThresholdOnce) {
  for (int by = 0; by < 3; ++by) {
    for (int bx = 0; bx < 3; ++bx) {
      std::vector<float> thresholds;
      for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x)
          thresholds.push_back(shaders::translucencyThreshold(4 * bx + x, 4 * by + y));
      }
      std::sort(thresholds.begin(), thresholds.end());
      for (int k = 0; k < 16; ++k) EXPECT_EQ(thresholds[size_t(k)], (float(k) + 0.5f) / 16.0f);
    }
  }
}

TEST(TranslucencyDither, ABlockCoversAlphaOfItsTexelsAndNeighboursSpreadOut) {
  for (int k = 0; k <= 16; ++k) {
    const float alpha = float(k) / 16.0f;
    int covered = 0;
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 4; ++x) covered += shaders::translucentCovers(alpha, x, y);
    }
    EXPECT_EQ(covered, k) << "alpha " << alpha;
  }
  // Ordered dither: at alpha 0.25 the covered texels of a block are not neighbours (a clump would
  // need a wider filter to average): each 2x2 quarter of the block holds exactly one.
  for (int qy = 0; qy < 2; ++qy) {
    for (int qx = 0; qx < 2; ++qx) {
      int covered = 0;
      for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 2; ++x)
          covered += shaders::translucentCovers(0.25f, 2 * qx + x, 2 * qy + y);
      }
      EXPECT_EQ(covered, 1) << "quarter " << qx << "," << qy;
    }
  }
}

}  // namespace
}  // namespace penumbra
