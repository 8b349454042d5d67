// StereoMatcher::create: algorithm name -> implementation, followed by the
// post-filters every algorithm gets (foreground fattening correction, gated
// mean), optionally wrapped in the reduced-resolution mode (match at half size,
// publish at full size).
#include "stereo_matcher.hpp"

#include "boundary_snap.hpp"
#include "box_resample.hpp"
#include "gated_mean.hpp"
#include "near_field.hpp"
#include "opencv_matchers.hpp"
#include "own_sgm.hpp"

namespace nerv::stereo {
namespace {

std::unique_ptr<StereoMatcher> createMatcher(const Params& p) {
  if (p.algorithm == "nerv_sgm") return createOwnSgm(p);
  if (p.algorithm == "sgbm_wls") return createWlsMatcher(p);
  return createOpenCvMatcher(p);
}

// Half the matching window: how far a window-based cost fattens an object.
int snapBand(const Params& p) {
  if (p.boundary_snap_px >= 0) return p.boundary_snap_px;
  if (p.algorithm == "nerv_sgm") return p.census_width / 2;
  if (p.algorithm == "bm") return p.bm_block_size / 2;
  return p.block_size / 2;
}

// Any matcher followed by the foreground fattening correction.
class BoundarySnapped : public StereoMatcher {
 public:
  BoundarySnapped(std::unique_ptr<StereoMatcher> inner, int band_px) : inner_(std::move(inner)) {
    params_.band_px = band_px;
  }
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    inner_->compute(left, right, disparity, confidence);
    snapDisparityBoundaries(left, disparity, confidence, params_);
  }
  std::string name() const override { return inner_->name(); }

 private:
  std::unique_ptr<StereoMatcher> inner_;
  BoundarySnapParams params_;
};

// Any matcher followed by the depth-gated mean, on the two image halves in
// parallel (each reads a copy taken before either is written: the result of
// one pass, whatever the thread count).
class GatedMeanFiltered : public StereoMatcher {
 public:
  GatedMeanFiltered(std::unique_ptr<StereoMatcher> inner, const Params& p) : inner_(std::move(inner)) {
    params_.radius = p.gated_mean_radius;
    params_.range_px = static_cast<float>(p.gated_mean_range_px);
    params_.range_rel = static_cast<float>(p.gated_mean_range_rel);
    threads_ = std::max(1, std::min(p.threads, 2));
  }
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    inner_->compute(left, right, disparity, confidence);
    disparity.copyTo(before_);
    const int rows = disparity.rows;
    cv::parallel_for_(cv::Range(0, 2), [&](const cv::Range& r) {
      for (int half = r.start; half < r.end; ++half)
        gatedMeanRows(before_, disparity, params_, rows * half / 2, rows * (half + 1) / 2);
    }, threads_);
  }
  std::string name() const override { return inner_->name(); }

 private:
  std::unique_ptr<StereoMatcher> inner_;
  GatedMeanParams params_;
  int threads_ = 2;
  cv::Mat before_;
};

std::unique_ptr<StereoMatcher> createFullResolution(const Params& p) {
  auto m = createMatcher(p);
  const int band = snapBand(p);
  if (band > 0) m = std::make_unique<BoundarySnapped>(std::move(m), band);
  if (p.gated_mean_radius > 0) m = std::make_unique<GatedMeanFiltered>(std::move(m), p);
  return m;
}

// For slow computers: both views are averaged down by 2 (2 x 2 blocks, box_resample.hpp),
// matched with half the range, and the disparity scaled back (values x2, each value
// repeated over its block, so invalid pixels stay invalid and edges stay sharp).
class ReducedResolution : public StereoMatcher {
 public:
  explicit ReducedResolution(Params p) {
    p.downscale = 1;  // the inner matcher's own checks see the halved range at its resolution
    p.num_disparities /= 2;
    p.min_disparity /= 2;
    p.speckle_window_size /= 4;
    p.block_size = std::max(3, (p.block_size / 2) | 1);
    p.bm_block_size = std::max(5, (p.bm_block_size / 2) | 1);
    inner_ = createFullResolution(p);
  }
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    boxMeanDownscale(left, 2, small_left_);
    boxMeanDownscale(right, 2, small_right_);
    inner_->compute(small_left_, small_right_, small_disparity_, small_confidence_);
    small_disparity_ *= 2.0;
    blockNearestUpscale(small_disparity_, 2, left.size(), disparity);
    blockNearestUpscale(small_confidence_, 2, left.size(), confidence);
  }
  std::string name() const override { return inner_->name() + "_half"; }

 private:
  std::unique_ptr<StereoMatcher> inner_;
  cv::Mat small_left_, small_right_, small_disparity_, small_confidence_;
};

// Any matcher followed by the near-field match (near_field.hpp): the same
// algorithm on both views averaged down by 4, disparities [0, 64) there, i.e.
// [0, 256) full-resolution pixels, fused where the main match cannot reach.
class NearFieldExtended : public StereoMatcher {
 public:
  NearFieldExtended(std::unique_ptr<StereoMatcher> inner, Params p) : inner_(std::move(inner)) {
    fuse_.scale = kScale;
    fuse_.reach_px = static_cast<float>(p.min_disparity + p.num_disparities);
    p.num_disparities = kLevels;
    p.min_disparity = 0;
    p.downscale = 1;
    p.near_field = false;
    p.speckle_window_size /= kScale * kScale;
    p.block_size = std::max(3, (p.block_size / kScale) | 1);
    p.bm_block_size = std::max(5, (p.bm_block_size / kScale) | 1);
    near_ = createFullResolution(p);
  }
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    inner_->compute(left, right, disparity, confidence);
    const cv::Size small((left.cols + kScale - 1) / kScale, (left.rows + kScale - 1) / kScale);
    // Too small to search 64 levels at a quarter (OpenCV's matchers refuse it): below
    // 512 x 64 px the main search alone.
    near_pixels_ = 0;
    if (small.width < 2 * kLevels || small.height < 16) return;
    boxMeanDownscale(left, kScale, small_left_);
    boxMeanDownscale(right, kScale, small_right_);
    near_->compute(small_left_, small_right_, near_disparity_, near_confidence_);
    near_pixels_ = fuseNearField(disparity, confidence, near_disparity_, near_confidence_, fuse_);
  }
  std::string name() const override { return inner_->name(); }
  int nearFieldPixels() const override { return near_pixels_; }

  static constexpr int kScale = 4, kLevels = 64;

 private:
  std::unique_ptr<StereoMatcher> inner_, near_;
  NearFieldParams fuse_;
  int near_pixels_ = 0;
  cv::Mat small_left_, small_right_, near_disparity_, near_confidence_;
};

}  // namespace

std::unique_ptr<StereoMatcher> StereoMatcher::create(const Params& params) {
  checkParams(params);
  std::unique_ptr<StereoMatcher> m = params.downscale == 2 ? std::make_unique<ReducedResolution>(params)
                                                           : createFullResolution(params);
  // Only where it can add something: it covers disparities up to 256 px (the wire's limit).
  if (params.near_field && params.min_disparity + params.num_disparities + 4 < 4 * NearFieldExtended::kLevels)
    m = std::make_unique<NearFieldExtended>(std::move(m), params);
  return m;
}

}  // namespace nerv::stereo
