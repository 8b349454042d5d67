// nerv's own semi-global matcher ("nerv_sgm"): center-symmetric census 9x7
// Hamming cost, 4 aggregation paths (left-right, right-left, top-down,
// bottom-up) in 8-bit saturating SIMD, two threads, equiangular subpixel,
// uniqueness test, left-right check and speckle removal.
//
// Passes, each split into tasks that the threads pull from a shared counter:
//   1. census of both images (tasks: bands of rows);
//   2. the top-down path over the upper half of the rows and the bottom-up
//      path over the lower half, over costs computed row by row; every k-th
//      row is kept as a checkpoint (tasks: direction x band of columns, as
//      columns are independent along vertical paths);
//   3. per half, in segments of k rows: the half's own vertical path
//      recomputed over the segment from its checkpoint, with the segment's
//      costs kept; then row by row, against the path's direction, the other
//      vertical path continued from where pass 2 left it (in a cache-resident
//      row), horizontal paths, average of the four, winners for the left and
//      right views, left-right check (tasks: the two halves, as the continued
//      path is sequential);
//   4. speckle removal on the two image halves.
// Memory: W * H * D / k bytes of checkpoints (about 7.5 MB at 1242 x 375 x 128,
// k = 8) and 2 * k * W * D bytes per thread.
#pragma once

#include <memory>

#include "stereo_matcher.hpp"

namespace nerv::stereo {

// Rows between the checkpoints pass 2 keeps of a half's first vertical path
// (pass 3 recomputes the path over each segment of this many rows): the
// segment's costs and path rows, 2 * k * W * D bytes, stay in cache (L2 and
// L3); 4 and 16 measured no faster than 8 (docs/stereo.md).
constexpr int kSgmSegmentRows = 8;

// Which code this build runs, for the service's start line and bench_stereo: e.g.
// "path steps and winners AVX2, census costs AVX-512 VPOPCNTDQ". Without AVX2 they run on
// 16-byte registers ("SSE4.1 (no AVX2)", "NEON (no AVX2)"), about twice the AVX2 build's time,
// or, without those too, in portable loops (docs/stereo.md "CPUs without AVX-512
// VPOPCNTDQ"), which is worth knowing when a matcher is slow.
const char* ownSgmCodePaths();

// use_simd = false runs the scalar aggregation (the SIMD-vs-scalar test);
// segment_rows: k, other than kSgmSegmentRows only in tests.
std::unique_ptr<StereoMatcher> createOwnSgm(const Params& params, bool use_simd = true,
                                            int segment_rows = kSgmSegmentRows);

}  // namespace nerv::stereo
