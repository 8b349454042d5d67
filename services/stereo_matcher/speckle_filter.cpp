#include "speckle_filter.hpp"

#include <opencv2/calib3d.hpp>

namespace nerv::stereo {

void removeSpeckles(cv::Mat& disparity, int window_px, int range_px) {
  if (window_px <= 0) return;
  CV_Assert(disparity.type() == CV_32FC1);
  cv::Mat fixed;
  disparity.convertTo(fixed, CV_16S, 16.0);  // 1/16 px steps, as OpenCV's matchers
  cv::filterSpeckles(fixed, 0, window_px, range_px * 16);
  disparity.setTo(0.0f, fixed == 0);
}

void removeSpeckles(cv::Mat& disparity, int window_px, int range_px, int row_begin, int row_end) {
  if (row_end <= row_begin) return;
  cv::Mat stripe = disparity.rowRange(row_begin, row_end);
  removeSpeckles(stripe, window_px, range_px);
}

}  // namespace nerv::stereo
