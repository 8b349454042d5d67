#include "speckle_filter.hpp"

#include <opencv2/calib3d.hpp>

namespace nerv::stereo {

void removeSpeckles(cv::Mat& disparity, cv::Mat* confidence, int window_px, int range_px,
                    int row_begin, int row_end, SpeckleScratch& scratch) {
  if (window_px <= 0 || row_end <= row_begin) return;
  CV_Assert(disparity.type() == CV_32FC1);
  cv::Mat stripe = disparity.rowRange(row_begin, row_end);
  cv::Mat& fixed = scratch.fixed;
  stripe.convertTo(fixed, CV_16S, 16.0);  // 1/16 px steps, as OpenCV's matchers
  cv::filterSpeckles(fixed, 0, window_px, range_px * 16, scratch.labels);
  for (int y = 0; y < stripe.rows; ++y) {
    const int16_t* f = fixed.ptr<int16_t>(y);
    float* d = stripe.ptr<float>(y);
    float* c = confidence ? confidence->ptr<float>(row_begin + y) : nullptr;
    for (int x = 0; x < stripe.cols; ++x)
      if (f[x] == 0) {
        d[x] = 0.0f;
        if (c) c[x] = 0.0f;
      }
  }
}

}  // namespace nerv::stereo
