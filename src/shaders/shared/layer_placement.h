// Lloyd relaxation of layer splits (thesis §4.1.2), the parts the GPU's passes and the CPU
// reference (src/core/layer_placement.cpp) share: the second-occluder sample of a 2x2 texel
// block, the cluster a sample joins, a step's update of the splits from its sums, when the
// relaxation has settled, and the splits it places.
#ifndef PENUMBRA_SHARED_LAYER_PLACEMENT_H
#define PENUMBRA_SHARED_LAYER_PLACEMENT_H
#include "layers.h"
#include "prelude.h"
PENUMBRA_BEGIN_SHARED

// Samples of weight at most this are flat footprints: no depth discontinuity to place a split at.
const float kMinSplitWeight = 0.000001f;

struct SecondOccluderSample {
  float depth;   // mu + sigma of the block: the farther depth when two depths share it
  float weight;  // sigma^2, zero for flat blocks and for blocks touching the empty far plane
};

// The sample of a 2x2 block of linear depths (thesis §4.1.2: "second occluder" mu + sigma,
// weighted by the variance). A block touching the cleared far plane (depth 1) is an edge against
// nothing and weighs nothing.
PENUMBRA_INLINE SecondOccluderSample secondOccluderSample(vec4 blockDepths) {
  float m1 = 0.0f;
  float m2 = 0.0f;
  bool empty = false;
  for (int i = 0; i < 4; ++i) {
    float z = blockDepths[i];
    m1 += 0.25f * z;
    m2 += 0.25f * z * z;
    empty = empty || z >= 1.0f;
  }
  PENUMBRA_PRECISE float variance = max(m2 - m1 * m1, 0.0f);
  SecondOccluderSample s;
  s.depth = m1 + sqrt(variance);
  s.weight = variance > kMinSplitWeight && !empty ? variance : 0.0f;
  return s;
}

// The cluster (interior split k, 0-based) nearest to `depth`, the first of equals.
PENUMBRA_INLINE int nearestSplit(LayerSplits splits, float depth) {
  int nearest = 0;
  for (int k = 1; k < splits.layerCount - 1; ++k) {
    if (abs(layerSplit(splits, k + 1) - depth) < abs(layerSplit(splits, nearest + 1) - depth)) {
      nearest = k;
    }
  }
  return nearest;
}

// What a Lloyd step gathers, per split (cluster k, 0-based) and per layer: the total weight and
// the weighted sum of depths of the samples that join it.
struct LloydStepSums {
  float clusterWeight[kMaxLayers];
  float clusterSum[kMaxLayers];
  float layerWeight[kMaxLayers];
  float layerSum[kMaxLayers];
};

// The GPU's sums (passes/lloyd_sums.comp, lloyd_step.comp): the quantities of a step's sums
// (cluster weights, cluster sums, layer weights, layer sums), and the rows of samples each sums
// group adds up. Equal, so that a group's invocation i adds quantity i over the group's rows.
const int kLloydQuantities = 4 * kMaxLayers;
const int kLloydRowsPerGroup = kLloydQuantities;

// The relaxation stops once no split moves by more than this in a step.
const float kLloydSettled = 0.000001f;

// How close two splits (and a split and 0 or 1) may come: two overlaps, so that neighbouring
// layers' widened ranges (overlappedLayerRange) do not cover each other's splits.
PENUMBRA_INLINE float lloydMinGap(float overlap) {
  return max(2.0f * overlap, 0.001f);
}

// Every index into a local array below is a constant once a loop over kMaxLayers unrolls; a
// count that varies (the layers, a rank, a teleport's turn) only takes part in comparisons. A
// run-time index makes a GPU compiler expand each access into a ladder over the whole array, and
// with the insertion sort and teleports written that way llvmpipe took 2.9-4.9 s to compile the
// step (passes/lloyd_step.comp), the largest part of a first `compare` (docs/results/
// passes-llvmpipe-2026-12-07.md).

// The interior splits of `candidate` sorted, kept strictly inside (0,1) and `minGap` apart:
// pushed forward from 0, then back from 1. The sort is stable: split i goes to its rank, the
// splits below it plus the equal ones before it.
PENUMBRA_INLINE LayerSplits packSplits(LayerSplits candidate, float minGap) {
  int n = candidate.layerCount - 1;
  float s[kMaxLayers - 1];
  int rank[kMaxLayers - 1];
  for (int i = 0; i < kMaxLayers - 1; ++i) s[i] = layerSplit(candidate, i + 1);
  for (int i = 0; i < kMaxLayers - 1; ++i) {
    rank[i] = 0;
    for (int j = 0; j < kMaxLayers - 1; ++j) {
      if (j < n && (s[j] < s[i] || (s[j] == s[i] && j < i))) ++rank[i];
    }
  }
  float sorted[kMaxLayers - 1];
  for (int r = 0; r < kMaxLayers - 1; ++r) {
    sorted[r] = 1.0f;
    for (int i = 0; i < kMaxLayers - 1; ++i) {
      if (i < n && rank[i] == r) sorted[r] = s[i];
    }
  }
  float previous = 0.0f;
  for (int i = 0; i < kMaxLayers - 1; ++i) {
    if (i < n) {
      sorted[i] = max(sorted[i], previous + minGap);
      previous = sorted[i];
    }
  }
  float next = 1.0f;
  for (int i = kMaxLayers - 2; i >= 0; --i) {
    if (i < n) {
      sorted[i] = min(sorted[i], next - minGap);
      next = sorted[i];
    }
  }
  LayerSplits spaced = uniformLayerSplits(candidate.layerCount);
  for (int k = 0; k < kMaxLayers - 1; ++k) {
    if (k < n) spaced.interior[k / 4][k % 4] = sorted[k];
  }
  return spaced;
}

// One Lloyd step's move: each split to its cluster's weighted mean. A split left with no weight
// is teleported (thesis: "merge the two adjacent layers and split whatever layer has the highest
// weight"): placed at the weighted mean of the heaviest layer (the first of equals), each empty
// split into a different layer; with no weight anywhere it keeps its place. Empty clusters
// teleport in their order; which slot a split takes does not matter, as packSplits sorts them.
PENUMBRA_INLINE LayerSplits lloydUpdate(LloydStepSums sums, LayerSplits splits, float minGap) {
  int n = splits.layerCount - 1;
  if (n <= 0) return splits;
  LayerSplits next = uniformLayerSplits(splits.layerCount);
  float layerWeight[kMaxLayers];
  for (int l = 0; l < kMaxLayers; ++l) layerWeight[l] = sums.layerWeight[l];
  int teleports = 0;  // empty clusters so far
  for (int k = 0; k < kMaxLayers - 1; ++k) {
    if (k >= n) continue;
    if (sums.clusterWeight[k] > 0.0f) {
      next.interior[k / 4][k % 4] = sums.clusterSum[k] / sums.clusterWeight[k];
      continue;
    }
    int heaviest = 0;
    float heaviestWeight = layerWeight[0];
    float heaviestSum = sums.layerSum[0];
    for (int l = 1; l < kMaxLayers; ++l) {
      if (l < splits.layerCount && layerWeight[l] > heaviestWeight) {
        heaviest = l;
        heaviestWeight = layerWeight[l];
        heaviestSum = sums.layerSum[l];
      }
    }
    float teleported = layerSplit(splits, teleports + 1);  // teleports < n
    if (heaviestWeight > 0.0f) {
      teleported = heaviestSum / heaviestWeight;
      for (int l = 0; l < kMaxLayers; ++l) {
        if (l == heaviest) layerWeight[l] = 0.0f;  // the next teleport goes elsewhere
      }
    }
    next.interior[k / 4][k % 4] = teleported;
    ++teleports;
  }
  return packSplits(next, minGap);
}

PENUMBRA_INLINE float largestSplitMove(LayerSplits a, LayerSplits b) {
  float moved = 0.0f;
  for (int k = 1; k < a.layerCount; ++k) {
    moved = max(moved, abs(layerSplit(a, k) - layerSplit(b, k)));
  }
  return moved;
}

// The splits a relaxation places: its centres sit at second occluders' mean depths, and a
// boundary exactly there would leave half of those surfaces in the layer in front, still
// bleeding, so each split moves `frontMargin` (one overlap) toward the light.
PENUMBRA_INLINE LayerSplits lloydPlacedSplits(LayerSplits relaxed, float frontMargin,
                                              float minGap) {
  LayerSplits moved = relaxed;
  for (int k = 0; k < kMaxLayers - 1; ++k) {
    if (k + 1 < relaxed.layerCount) {
      moved.interior[k / 4][k % 4] = layerSplit(relaxed, k + 1) - frontMargin;
    }
  }
  return packSplits(moved, minGap);
}

// The GPU relaxation's state between its passes (passes/lloyd_step.comp): the splits, whether
// they settled, and after the last step the placed splits with the encode's texel-layer ranges
// for them (lvsmTexelLayerRanges), laid out as the parameter blocks hold them, which copy them
// there.
struct LloydState {
  LayerSplits splits;
  int settled;
  int pad0;
  int pad1;
  int pad2;
  vec4 texelLayerRanges[kMaxTexelLayers];
};

PENUMBRA_END_SHARED
#endif
