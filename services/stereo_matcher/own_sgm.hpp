// nerv's own semi-global matcher ("nerv_sgm"): center-symmetric census 9x7
// Hamming cost, 4 aggregation paths (left-right, right-left, top-down,
// bottom-up) in 8-bit saturating SIMD, two threads, equiangular subpixel,
// uniqueness test, left-right check and speckle removal.
//
// Passes, each split into tasks that the threads pull from a shared counter:
//   1. census of both images (tasks: bands of rows);
//   2. the top-down path over the upper half of the rows and the bottom-up
//      path over the lower half, over costs computed row by row, streamed
//      into one W x H x D byte volume (tasks: direction x band of columns, as
//      columns are independent along vertical paths);
//   3. per half, row by row: costs again, the other vertical path continued
//      from where pass 2 left it (in a cache-resident row), horizontal paths,
//      average of the four, winners for the left and right views, left-right
//      check (tasks: the two halves, as the continued path is sequential);
//   4. speckle removal on the two image halves.
// Memory: W * H * D bytes (about 60 MB at 1242 x 375 x 128).
#pragma once

#include <memory>

#include "stereo_matcher.hpp"

namespace nerv::stereo {

// use_simd = false runs the scalar aggregation (the SIMD-vs-scalar test).
std::unique_ptr<StereoMatcher> createOwnSgm(const Params& params, bool use_simd = true);

}  // namespace nerv::stereo
