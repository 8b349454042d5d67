// sgbm_wls: SGBM (3-way) on both views, then ximgproc's weighted-least-squares
// disparity filter (Min et al. 2014, "Fast global image smoothing based on WLS")
// guided by the left image. The right-view matcher gives the filter its
// left-right confidence map, which nerv publishes as the per-pixel confidence.
#include <opencv2/calib3d.hpp>
#include <opencv2/ximgproc/disparity_filter.hpp>

#include "opencv_matchers.hpp"

namespace nerv::stereo {
namespace {

class WlsMatcher : public StereoMatcher {
 public:
  explicit WlsMatcher(const Params& p) : params_(p) {
    left_ = cv::StereoSGBM::create(p.min_disparity, p.num_disparities, p.block_size, p.p1, p.p2,
                                   p.lr_max_diff, 0, p.uniqueness_ratio, p.speckle_window_size,
                                   p.speckle_range, cv::StereoSGBM::MODE_SGBM_3WAY);
    right_ = cv::ximgproc::createRightMatcher(left_);
    filter_ = cv::ximgproc::createDisparityWLSFilter(left_);
    filter_->setLambda(p.wls_lambda);
    filter_->setSigmaColor(p.wls_sigma);
  }
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    left_->compute(left, right, fixed_left_);
    right_->compute(right, left, fixed_right_);
    filter_->filter(fixed_left_, left, filtered_, fixed_right_);
    fixedToFloat(filtered_, params_.min_disparity, disparity);
    // confidence map: CV_32F 0..255 (ximgproc)
    filter_->getConfidenceMap().convertTo(confidence, CV_32F, 1.0 / 255.0);
    confidence.setTo(0.0f, disparity == 0.0f);
  }
  std::string name() const override { return "sgbm_wls"; }

 private:
  Params params_;
  cv::Ptr<cv::StereoSGBM> left_;
  cv::Ptr<cv::StereoMatcher> right_;
  cv::Ptr<cv::ximgproc::DisparityWLSFilter> filter_;
  cv::Mat fixed_left_, fixed_right_, filtered_;
};

}  // namespace

std::unique_ptr<StereoMatcher> createWlsMatcher(const Params& params) {
  return std::make_unique<WlsMatcher>(params);
}

}  // namespace nerv::stereo
