// Evaluates the shared technique dispatcher on the GPU for the parity test: one invocation per
// case, the same function the C++ reference runs (src/shaders/shared/technique_dispatch.h).
#include "shared/technique_dispatch.h"

layout(local_size_x = 64) in;

struct ParityCase {
  int penumbraTechnique;
  float receiverDepth;
  int pad0;
  int pad1;
  float channels[kMaxChannels];
};

layout(std430, binding = 0) readonly buffer Cases {
  ParityCase cases[];
};
layout(std430, binding = 1) readonly buffer ParamSets {
  TechniqueParams paramSets[];
};
layout(std430, binding = 2) writeonly buffer Results {
  float visibility[];
};

uniform uint caseCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= caseCount) return;
  ParityCase c = cases[i];
  // The dispatcher's array: all kMaxChannels unless a variant sizes it (PENUMBRA_CHANNEL_CAPACITY).
  float channels[PENUMBRA_CHANNEL_CAPACITY];
  for (int k = 0; k < PENUMBRA_CHANNEL_CAPACITY; ++k) channels[k] = c.channels[k];
  visibility[i] = reconstructVisibility(c.penumbraTechnique, channels, c.receiverDepth, paramSets[i]);
}
