// Stereo pair -> dense subpixel disparity of the left view. One small
// interface, implementations behind create() (as OpenCV's StereoMatcher).
#pragma once

#include <opencv2/core.hpp>

#include <memory>
#include <string>

#include "config.hpp"

namespace nerv::stereo {

struct Params {
  std::string algorithm = "sgbm";  // "sgbm" (3-way) | "sgbm_full" | "bm"
  int num_disparities = 128;       // search range [px], multiple of 16
  int min_disparity = 0;           // smallest disparity searched [px]
  int block_size = 5;              // matching window (odd)
  int p1 = 8 * 25;                 // SGM penalty for disparity changes of 1 (block 5, gray)
  int p2 = 32 * 25;                // SGM penalty for larger changes
  int uniqueness_ratio = 10;       // [%] best cost must beat the second best by this margin
  int speckle_window_size = 100;   // connected regions smaller than this are invalidated [px]
  int speckle_range = 2;           // max disparity variation within a region [px]
  int lr_max_diff = 1;             // left-right check tolerance [px]; < 0 disables it
};

Params readParams(ConfigSection& section);

class StereoMatcher {
 public:
  virtual ~StereoMatcher() = default;
  // left, right: 8-bit gray, same size, rectified. disparity: CV_32F [px],
  // 0 where invalid.
  virtual void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity) = 0;
  virtual std::string name() const = 0;

  static std::unique_ptr<StereoMatcher> create(const Params& params);
};

}  // namespace nerv::stereo
