// Speckle removal: small connected regions of similar disparity, mostly
// mismatches on weak texture, are invalidated (the rule of OpenCV's
// filterSpeckles on the fixed-point map).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace nerv::stereo {

// disparity: CV_32F [px], 0 invalid. Regions of at most window_px pixels
// whose neighbours differ by <= range_px are set to 0, and so is the
// confidence there when `confidence` (CV_32F, same size) is given. Only rows
// [row_begin, row_end) are looked at (a region cut by the stripe border counts
// per stripe), so stripes can be filtered on separate threads. window_px <= 0:
// no-op. scratch: buffers kept between calls (fresh ones cost page faults).
struct SpeckleScratch {
  cv::Mat fixed, labels;
  std::vector<int> parent, run_begin, run_length, region_size;
};
void removeSpeckles(cv::Mat& disparity, cv::Mat* confidence, int window_px, int range_px,
                    int row_begin, int row_end, SpeckleScratch& scratch);

// The whole image.
inline void removeSpeckles(cv::Mat& disparity, int window_px, int range_px) {
  SpeckleScratch scratch;
  removeSpeckles(disparity, nullptr, window_px, range_px, 0, disparity.rows, scratch);
}

}  // namespace nerv::stereo
