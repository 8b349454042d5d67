// Depth-gated mean of a disparity map (docs/stereo.md "Gated mean"): every valid
// pixel takes the mean of the valid disparities of its (2r+1)^2 window that lie
// within a gate of its own value, gate = max(range_px, range_rel * d). It averages
// out the winners' per-pixel subpixel scatter on a surface (a plane's disparity is
// linear in the image, so a symmetric window leaves it unbiased) without mixing
// the two sides of a depth edge: the gate is a share of the disparity, i.e. a
// share of the depth (5 % by default), so a cyclist 2.5 m in front of a car at
// 30 m is not averaged with it. Invalid pixels (<= 0) stay invalid.
#pragma once

#include <opencv2/core.hpp>

namespace nerv::stereo {

struct GatedMeanParams {
  int radius = 2;           // window radius [px]; 0 = off
  float range_px = 0.5f;    // smallest gate [px]
  float range_rel = 0.05f;  // gate as a share of the pixel's disparity
};

// Filters rows [row_begin, row_end) of `disparity` (CV_32F) reading only
// `before`, a copy of the whole map taken before any row was written, so that
// row ranges can run in parallel and give the result of one call over all rows.
void gatedMeanRows(const cv::Mat& before, cv::Mat& disparity, const GatedMeanParams& params, int row_begin,
                   int row_end);

}  // namespace nerv::stereo
