// One Lloyd step of layered VSM's split placement (thesis §4.1.2), on the GPU: the sums
// (passes/lloyd_sums.comp, one partial per group of rows) added up, the splits moved to their
// clusters' weighted means (shared lloydUpdate), and after the last step the placed splits and
// the encode's texel-layer ranges for them, which the renderer copies into its parameter
// blocks. Nothing is read back: a frame waits for no step (the CPU reference:
// src/core/layer_placement.cpp).
#include "../shared/layer_placement.h"
#include "../shared/lvsm.h"

// One invocation per quantity of the sums, each adding the sums groups' partials: one small
// group, whose barrier stays cheap where a CPU runs it
// (docs/results/lloyd-gpu-llvmpipe-2026-12-07.md).
layout(local_size_x = kLloydQuantities) in;
layout(std430, binding = 2) readonly buffer Sums {
  float sums[];
};
layout(std430, binding = 4) buffer State {
  LloydState state;
};

uniform int groupCount;  // of the sums pass
uniform float overlap;   // LvsmParams::overlap
uniform bool lastStep;

shared float totals[kLloydQuantities];

void main() {
  int quantity = int(gl_LocalInvocationID.x);
  bool settled = state.settled != 0;
  float t = 0.0f;
  if (!settled) {
    for (int g = 0; g < groupCount; ++g) t += sums[g * kLloydQuantities + quantity];
  }
  totals[quantity] = t;
  barrier();
  if (quantity != 0) return;
  float minGap = lloydMinGap(overlap);
  LayerSplits splits = state.splits;
  if (!settled) {
    LloydStepSums s;
    for (int i = 0; i < kMaxLayers; ++i) {
      s.clusterWeight[i] = totals[i];
      s.clusterSum[i] = totals[kMaxLayers + i];
      s.layerWeight[i] = totals[2 * kMaxLayers + i];
      s.layerSum[i] = totals[3 * kMaxLayers + i];
    }
    LayerSplits next = lloydUpdate(s, splits, minGap);
    state.settled = largestSplitMove(next, splits) < kLloydSettled ? 1 : 0;
    splits = next;
    state.splits = next;
  }
  if (lastStep) {
    LayerSplits placed = lloydPlacedSplits(splits, overlap, minGap);
    state.splits = placed;
    for (int l = 0; l < kMaxTexelLayers; ++l) {
      state.texelLayerRanges[l] = lvsmTexelLayerRanges(l, placed, overlap);
    }
  }
}
