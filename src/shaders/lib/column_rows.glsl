// The texels a pass invocation covers when it works ROWS_PER_INVOCATION texels of one column, a
// work group's height apart, so that a group's lanes still cover rows of adjacent texels: the
// encode and its minimal copy (bench --passes) walk the same texels. llvmpipe pays for every
// uniform element an invocation reads, and without MSAA an invocation's reads serve all its rows
// (gl/channel_dispatch.h encodeRowsPerInvocation; docs/results/passes-llvmpipe-2026-12-06-rows.md).
// The dispatch covers the map's height in groups of ROWS_PER_INVOCATION x the group's height
// (encodeGroups).
#ifndef PENUMBRA_LIB_COLUMN_ROWS_GLSL
#define PENUMBRA_LIB_COLUMN_ROWS_GLSL
const int kRows = ROWS_PER_INVOCATION;

// The row of the invocation's k-th texel (k < kRows); rows past the map's edge are the caller's
// to clamp or skip.
int invocationRow(int k) {
  int firstRow = int(gl_WorkGroupID.y * gl_WorkGroupSize.y) * kRows + int(gl_LocalInvocationID.y);
  return firstRow + k * int(gl_WorkGroupSize.y);
}

// The row the k-th texel reads: rows past the map's edge (height rows) read its last row, so
// that no fetch leaves the map; their stores fall outside it and have no effect (GL 4.5 §8.26).
int invocationFetchRow(int k, int height) {
  return min(invocationRow(k), height - 1);
}
#endif
