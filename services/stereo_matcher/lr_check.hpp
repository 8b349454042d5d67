// Left-right consistency check: a left match d at x is kept only when the right
// view's best match at x - min_disparity - d points back to within max_diff.
// Occluded pixels (seen by the left camera only) fail it.
#pragma once

#include <cstdint>

namespace nerv::stereo {

// best_left / best_right: disparity indices (d - min_disparity) of one row, -1
// invalid. Invalidates disparity[x] = -1 and confidence[x] = 0 where the check fails.
void leftRightCheckRow(const int16_t* best_left, const int16_t* best_right, int cols,
                       int min_disparity, int max_diff, float* disparity, float* confidence);

}  // namespace nerv::stereo
