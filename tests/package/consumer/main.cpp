// Uses the installed API and the installed shared header directly, as an engine would.
#include <penumbra/depth_distribution.h>
#include <penumbra/technique.h>
#include <penumbra/shared/vsm.h>

#include <cstdio>
#include <vector>

int main() {
  const penumbra::TechniqueParams params = penumbra::defaultTechniqueParams();
  const std::vector<penumbra::DepthSample> region{{0.2f, 0.5f}, {0.6f, 0.5f}};
  const float v = penumbra::evaluateOnRegion(penumbra::Technique::Vsm, params, region, 0.6f);
  const float direct =
      penumbra::shaders::chebyshevUpperBound(penumbra::shaders::vsmEncode(0.4f), 0.3f, 0.0f);
  std::printf("vsm %.4f direct %.1f\n", v, direct);
  return (v > 0.4f && v < 0.6f && direct == 1.0f) ? 0 : 1;
}
