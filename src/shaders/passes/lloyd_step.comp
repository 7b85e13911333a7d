// One Lloyd step of layered VSM's split placement (thesis §4.1.2), on the GPU: the rows' sums
// (passes/lloyd_sums.comp) added up, the splits moved to their clusters' weighted means
// (shared lloydUpdate), and after the last step the placed splits and the encode's texel-layer
// ranges for them, which the renderer copies into its parameter blocks. Nothing is read back:
// a frame waits for no step (the CPU reference reads its sums: src/core/layer_placement.cpp).
#include "../lib/technique_block.glsl"
#include "../shared/layer_placement.h"

// x: the 64 (4 * kMaxLayers) quantities of a row's sums (cluster weights, cluster sums, layer
// weights, layer sums); y: 16 groups of rows, each invocation adding every 16th row.
layout(local_size_x = 64, local_size_y = 16) in;
layout(std430, binding = 2) readonly buffer Sums {
  float sums[];
};
layout(std430, binding = 4) buffer State {
  LloydState state;
};

uniform int rowCount;
uniform bool lastStep;

shared float partial[16][64];

// A quantity's total over every row, the groups added in order.
float total(int quantity) {
  float t = 0.0f;
  for (int g = 0; g < 16; ++g) t += partial[g][quantity];
  return t;
}

void main() {
  int quantity = int(gl_LocalInvocationID.x);
  int group = int(gl_LocalInvocationID.y);
  bool settled = state.settled != 0;
  float t = 0.0f;
  if (!settled) {
    for (int row = group; row < rowCount; row += 16) t += sums[row * 64 + quantity];
  }
  partial[group][quantity] = t;
  barrier();
  if (quantity != 0 || group != 0) return;
  float minGap = lloydMinGap(penumbraParams.lvsm.overlap);
  LayerSplits splits = state.splits;
  if (!settled) {
    LloydStepSums s;
    for (int i = 0; i < kMaxLayers; ++i) {
      s.clusterWeight[i] = total(i);
      s.clusterSum[i] = total(kMaxLayers + i);
      s.layerWeight[i] = total(2 * kMaxLayers + i);
      s.layerSum[i] = total(3 * kMaxLayers + i);
    }
    LayerSplits next = lloydUpdate(s, splits, minGap);
    state.settled = largestSplitMove(next, splits) < kLloydSettled ? 1 : 0;
    splits = next;
    state.splits = next;
  }
  if (lastStep) {
    TechniqueParams p = penumbraParams;
    p.lvsm.splits = lloydPlacedSplits(splits, p.lvsm.overlap, minGap);
    state.splits = p.lvsm.splits;
    for (int l = 0; l < kMaxTexelLayers; ++l) {
      state.texelLayerRanges[l] = texelLayerRanges(kTechniqueLvsm, l, p);
    }
  }
}
