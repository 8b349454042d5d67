// StereoMatcher implementations over OpenCV's block matcher (bm), semi-global
// block matcher (sgbm = 3-way, sgbm_full = 8-path MODE_HH) and SGBM followed by
// the ximgproc WLS disparity filter (sgbm_wls).
#pragma once

#include <memory>

#include "stereo_matcher.hpp"

namespace nerv::stereo {

std::unique_ptr<StereoMatcher> createOpenCvMatcher(const Params& params);  // bm, sgbm, sgbm_full
std::unique_ptr<StereoMatcher> createWlsMatcher(const Params& params);     // sgbm_wls

// OpenCV returns disparity * 16 (StereoMatcher::DISP_SCALE) in CV_16S; values
// below min_disparity are invalid. -> CV_32F [px], 0 invalid.
void fixedToFloat(const cv::Mat& fixed16, int min_disparity, cv::Mat& disparity);

}  // namespace nerv::stereo
