// One Lloyd step's sums for layered VSM split placement (thesis §4.1.2), one invocation per row
// of samples: for each split (cluster) and each layer, the total weight and weighted depth of
// the samples that join it, as accumulateLloyd (src/core/layer_placement.cpp) gathers them. A
// row holds only its weighted samples (passes/split_samples.comp), in the order the CPU meets
// them: the ones it skips added nothing. Each group adds its rows' sums in shared memory, so that
// the step (passes/lloyd_step.comp) adds one partial per group, not one per row.
#include "../shared/layer_placement.h"

layout(local_size_x = kLloydRowsPerGroup) in;
layout(std430, binding = 1) readonly buffer Samples {
  vec2 samples[];
};
// Per group: cluster weights, cluster sums, layer weights, layer sums, kMaxLayers entries each.
layout(std430, binding = 2) writeonly buffer Sums {
  float sums[];
};
layout(std430, binding = 3) readonly buffer RowCounts {
  int rowCounts[];
};
// The splits this step moves (passes/lloyd_step.comp); once they settle, the steps left do nothing.
layout(std430, binding = 4) readonly buffer State {
  LloydState state;
};

uniform int rowCount;
uniform int rowLength;

shared float rowSums[kLloydRowsPerGroup][kLloydQuantities];

void main() {
  int local = int(gl_LocalInvocationID.x);
  int row = int(gl_GlobalInvocationID.x);
  LayerSplits splits = state.splits;
  float clusterWeight[kMaxLayers];
  float clusterSum[kMaxLayers];
  float layerWeight[kMaxLayers];
  float layerSum[kMaxLayers];
  for (int i = 0; i < kMaxLayers; ++i) {
    clusterWeight[i] = 0.0f;
    clusterSum[i] = 0.0f;
    layerWeight[i] = 0.0f;
    layerSum[i] = 0.0f;
  }
  // Settled splits (the same for the whole dispatch) take no more sums: the step skips them.
  bool adds = state.settled == 0 && splits.layerCount >= 2 && row < rowCount;
  int count = adds ? rowCounts[row] : 0;
  for (int x = 0; x < count; ++x) {
    vec2 entry = samples[row * rowLength + x];
    float depth = entry.x;
    float weight = entry.y;
    int nearest = nearestSplit(splits, depth);
    clusterWeight[nearest] += weight;
    clusterSum[nearest] += weight * depth;
    int layer = selectLayer(depth, splits);
    layerWeight[layer] += weight;
    layerSum[layer] += weight * depth;
  }
  for (int i = 0; i < kMaxLayers; ++i) {
    rowSums[local][i] = clusterWeight[i];
    rowSums[local][kMaxLayers + i] = clusterSum[i];
    rowSums[local][2 * kMaxLayers + i] = layerWeight[i];
    rowSums[local][3 * kMaxLayers + i] = layerSum[i];
  }
  barrier();
  // Invocation q adds quantity q over the group's rows, in order (kLloydRowsPerGroup equals
  // kLloydQuantities).
  float total = 0.0f;
  for (int r = 0; r < kLloydRowsPerGroup; ++r) total += rowSums[r][local];
  sums[int(gl_WorkGroupID.x) * kLloydQuantities + local] = total;
}
