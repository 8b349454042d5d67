// Stereo pair -> dense subpixel disparity of the left view. One small
// interface, implementations behind create() (as OpenCV's StereoMatcher).
#pragma once

#include <opencv2/core.hpp>

#include <memory>
#include <string>

#include "config.hpp"

namespace nerv::stereo {

// Every field has a default; readParams() checks ranges and names bad keys.
struct Params {
  // "nerv_sgm" (own census SGM, 4 paths, SIMD, threads) | "sgbm" (OpenCV 3-way)
  // | "sgbm_full" (OpenCV, full 8-path MODE_HH) | "sgbm_wls" (SGBM + ximgproc WLS
  // filter with the right-view matcher) | "bm" (OpenCV block matcher).
  // Default chosen by measurement on kitti2015_000005, see docs/stereo.md.
  std::string algorithm = "nerv_sgm";
  int num_disparities = 128;       // search range [px], multiple of 16
  int min_disparity = 0;           // smallest disparity searched [px]
  int downscale = 1;               // 1 = full resolution; 2 = match at half resolution, publish at full
  int uniqueness_ratio = 10;       // [%] best cost must beat the second best (|d - best| > 1) by this margin
  int speckle_window_size = 100;   // connected regions smaller than this are invalidated [px]; 0 = off
  int speckle_range = 2;           // max disparity variation within a region [px]
  int lr_max_diff = 1;             // left-right check tolerance [px]; < 0 disables it
  // OpenCV matchers (bm, sgbm*)
  int block_size = 5;              // SGBM matching window (odd)
  int bm_block_size = 15;          // StereoBM window (odd, 5..255): BM needs a larger one than SGBM
  int p1 = 8 * 25;                 // SGBM penalty for disparity changes of 1 (block 5, gray)
  int p2 = 32 * 25;                // SGBM penalty for larger changes
  double wls_lambda = 8000.0;      // sgbm_wls: smoothness strength of the WLS filter
  double wls_sigma = 1.5;          // sgbm_wls: edge sensitivity of the WLS filter (colour sigma)
  // nerv_sgm
  int census_width = 9;            // center-symmetric census window (odd); (w * h - 1) / 2 <= 32 bits
  int census_height = 7;
  // Rows from road_census_from (share of the image height, counted from the top) down
  // use a flat window instead: there a vehicle camera sees mostly road, whose disparity
  // grows ~0.3 px per row, and a 7-row window spanning +-1 px of it flattened the road
  // (pitch +0.2 deg in snv_extrinsic); 3 rows do not (docs/stereo.md "Road accuracy").
  int road_census_width = 13;      // census window of the road band (odd, <= 32 pairs)
  int road_census_height = 3;
  double road_census_from = 0.72;  // first row of the road band / image height; 1 = no band
  bool flat_census_invalid = true;  // no disparity where the left census code is 0 and the pixel saturated (glare, clipped sky: no texture to match; own_sgm.cpp)
  int sgm_p1 = 7;                  // penalty for a disparity change of 1 [census bits]
  int sgm_p2 = 90;                 // penalty for larger changes [census bits]; bits + p2 <= 255
  bool subpixel = true;            // equiangular fit on the aggregated cost; false: integer disparities
  int threads = 2;                 // worker threads of nerv_sgm (1 = run on the caller's thread)
  // Foreground fattening correction (boundary_snap.hpp): how far inside an object's
  // disparity boundary its true (intensity) edge may lie [px]. -1 = half the matching
  // window of the algorithm (census_width / 2, block_size / 2); 0 = off.
  int boundary_snap_px = -1;
  // Depth-gated mean after every other filter (gated_mean.hpp, docs/stereo.md "Gated
  // mean"): window radius [px] (0 = off) and the gate, max(range_px, range_rel * d).
  int gated_mean_radius = 2;
  double gated_mean_range_px = 0.5;
  double gated_mean_range_rel = 0.05;
  // A second match at a quarter of the resolution over [0, 256) full-resolution px,
  // fused where surfaces are nearer than min_disparity + num_disparities reaches
  // (near_field.hpp, docs/stereo.md "Near field").
  bool near_field = true;
};

// First row of nerv_sgm's road band in an image of `rows` rows (rows when there is none).
int roadCensusRow(const Params& params, int rows);

// Every field that changes the disparity (all but `threads`), as one canonical
// string: the key of a disparity cache (bench_detection, bench_road_disparity).
std::string describeParams(const Params& params);

// Declares and reads the keys of the stereo_matcher section; ConfigError names the bad key.
Params readParams(ConfigSection& section);
// Throws ConfigError (naming the key under `path`) when the combination is unusable.
void checkParams(const Params& params, const std::string& path = "stereo_matcher");

class StereoMatcher {
 public:
  virtual ~StereoMatcher() = default;
  // left, right: 8-bit gray, same size, rectified. disparity: CV_32F [px], 0 where
  // invalid. confidence: CV_32F 0..1 of the same size (0 where invalid).
  virtual void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
                       cv::Mat& confidence) = 0;
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity) {
    compute(left, right, disparity, scratch_confidence_);
  }
  virtual std::string name() const = 0;
  // Pixels of the last compute() that the near-field match filled (near_field.hpp; 0 when off).
  virtual int nearFieldPixels() const { return 0; }

  // Throws ConfigError for an unknown algorithm or unusable parameters.
  static std::unique_ptr<StereoMatcher> create(const Params& params);

 private:
  cv::Mat scratch_confidence_;
};

}  // namespace nerv::stereo
