#include "opencv_matchers.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace nerv::stereo {

void fixedToFloat(const cv::Mat& fixed16, int min_disparity, cv::Mat& disparity) {
  fixed16.convertTo(disparity, CV_32F, 1.0 / cv::StereoMatcher::DISP_SCALE);
  cv::Mat invalid = disparity < std::max(min_disparity, 0) + 0.0f;
  disparity.setTo(0.0f, invalid);
}

namespace {

// OpenCV's matchers have no per-pixel confidence of their own: 1 where the
// matcher kept a disparity (after its uniqueness and left-right checks), else 0.
void validityConfidence(const cv::Mat& disparity, cv::Mat& confidence) {
  confidence.create(disparity.size(), CV_32FC1);
  confidence.setTo(0.0f);
  confidence.setTo(1.0f, disparity > 0.0f);
}

class SgbmMatcher : public StereoMatcher {
 public:
  explicit SgbmMatcher(const Params& p) : params_(p) {
    const int mode =
        p.algorithm == "sgbm_full" ? cv::StereoSGBM::MODE_HH : cv::StereoSGBM::MODE_SGBM_3WAY;
    sgbm_ = cv::StereoSGBM::create(p.min_disparity, p.num_disparities, p.block_size, p.p1, p.p2,
                                   p.lr_max_diff, 0, p.uniqueness_ratio, p.speckle_window_size,
                                   p.speckle_range, mode);
  }
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    sgbm_->compute(left, right, fixed_);
    fixedToFloat(fixed_, params_.min_disparity, disparity);
    validityConfidence(disparity, confidence);
  }
  std::string name() const override { return params_.algorithm; }

 private:
  Params params_;
  cv::Ptr<cv::StereoSGBM> sgbm_;
  cv::Mat fixed_;
};

class BmMatcher : public StereoMatcher {
 public:
  explicit BmMatcher(const Params& p) : params_(p) {
    bm_ = cv::StereoBM::create(p.num_disparities, p.bm_block_size);
    bm_->setMinDisparity(p.min_disparity);
    bm_->setUniquenessRatio(p.uniqueness_ratio);
    bm_->setSpeckleWindowSize(p.speckle_window_size);
    bm_->setSpeckleRange(p.speckle_range);
    bm_->setDisp12MaxDiff(p.lr_max_diff);
    bm_->setTextureThreshold(10);
  }
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    // The config cannot know the frame: a window larger than it is said per frame with its key
    // (OpenCV's own message names SADWindowSize).
    if (params_.bm_block_size > std::min(left.rows, left.cols))
      throw std::invalid_argument("config key 'stereo_matcher.bm_block_size' = " + std::to_string(params_.bm_block_size) +
                                  " is larger than the " + std::to_string(left.cols) + "x" +
                                  std::to_string(left.rows) + " frame");
    bm_->compute(left, right, fixed_);
    fixedToFloat(fixed_, params_.min_disparity, disparity);
    validityConfidence(disparity, confidence);
  }
  std::string name() const override { return "bm"; }

 private:
  Params params_;
  cv::Ptr<cv::StereoBM> bm_;
  cv::Mat fixed_;
};

}  // namespace

std::unique_ptr<StereoMatcher> createOpenCvMatcher(const Params& params) {
  if (params.algorithm == "bm") return std::make_unique<BmMatcher>(params);
  return std::make_unique<SgbmMatcher>(params);
}

}  // namespace nerv::stereo
