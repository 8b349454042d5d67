// 3x3 median of a disparity map with the fill of isolated holes (nerv_sgm's
// post-filter; docs/stereo.md "Post-filter"): a valid pixel takes the median
// of its 3x3 neighbourhood (cv::medianBlur, invalid = 0 counted as a value),
// an invalid pixel takes it only when at least 6 of its 8 neighbours are
// valid, with the lowest confidence among them.
#pragma once

#include <opencv2/core.hpp>

namespace nerv::stereo {

// Filters rows [row_begin, row_end) of `disparity` (CV_32F) and `confidence`
// (CV_32F, same size) in place. `before` is a copy of the whole disparity map
// taken before any row was filtered, so that row ranges can run in parallel
// and give the same result as one call over all rows. `scratch` is reused.
void medianFillRows(const cv::Mat& before, cv::Mat& disparity, cv::Mat& confidence, int row_begin,
                    int row_end, cv::Mat& scratch);

}  // namespace nerv::stereo
