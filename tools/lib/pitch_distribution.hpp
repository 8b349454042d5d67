// The ground-normal pitch distribution of one frame, recomputed from its
// logged disparity and the stixel ground model: EXTRINSICS carries only the
// histogram's mode, mean and mean-shift value, not the histogram. Ground
// samples are chosen as the snv stage does (ground_samples.hpp: below the
// horizon, |d - d_g(v)| <= max(1 px, 5 % d_g), depth 2..30 m, normal within 20
// deg of the camera's -y axis), but the normals are the plain cross-product
// ones of normal_needles.hpp, not the integral-image normals, so the shape is
// a close picture of the service's histogram, not a copy of it.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "nerv/ground_model_t.hpp"
#include "normal_needles.hpp"
#include "stereo_camera.hpp"

namespace nerv::viz {

struct PitchDistributionParams {
  int interval_px = 4;
  float bin_deg = 0.1f;
  float min_depth_m = 2.0f, max_depth_m = 30.0f;
  float disparity_tol_px = 1.0f, disparity_tol_rel = 0.05f;
  float prior_cone_deg = 20.0f;
};

struct PitchDistribution {
  std::vector<float> pitch_deg;  // one per ground sample: atan2(-n_z, -n_y) [deg]
  float origin_deg = 0;          // left edge of bin 0 [deg]
  float bin_deg = 0.1f;
  std::vector<double> counts;
  float mode_deg = 0, mean_deg = 0;  // of this recomputed distribution (NaN when empty)
};

// Empty distribution when the ground model is invalid or no sample qualifies.
PitchDistribution computePitchDistribution(const cv::Mat& disparity, const StereoCamera& cam,
                                           const ground_model_t& ground,
                                           const PitchDistributionParams& params = {});

}  // namespace nerv::viz
