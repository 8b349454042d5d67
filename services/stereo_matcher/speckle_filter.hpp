// Speckle removal: small connected regions of similar disparity, mostly
// mismatches on weak texture, are invalidated (OpenCV's filterSpeckles on the
// fixed-point map).
#pragma once

#include <opencv2/core.hpp>

namespace nerv::stereo {

// disparity: CV_32F [px], 0 invalid. Regions of fewer than window_px pixels
// whose neighbours differ by <= range_px are set to 0. window_px <= 0: no-op.
void removeSpeckles(cv::Mat& disparity, int window_px, int range_px);

// The same on the rows [row_begin, row_end) alone (a region cut by the stripe
// border counts per stripe), so stripes can be filtered on separate threads.
void removeSpeckles(cv::Mat& disparity, int window_px, int range_px, int row_begin, int row_end);

}  // namespace nerv::stereo
