// Which pixels sample the road for the super-SNV pose (NERV slides 22-24).
//
// With a valid stixel ground model: grid pixels below the horizon whose
// disparity lies within max(disparity_tol_px, disparity_tol_rel * d_g) of the
// model's ground disparity d_g(v) = GroundModel::groundDisparity(v).
// Without one: grid pixels at least lower_margin_px below the principal point.
// In both cases only points nearer than max_depth_m (the normals of a nearly
// horizontal road seen at a grazing angle get noisy fast with distance) and
// normals within prior_cone_deg of the camera's -y axis (a car is never
// pitched or rolled more than that) are kept.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "integral_normals.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::snv {

struct GroundSampleParams {
  float max_depth_m = 30.0f;        // ground samples farther away are ignored [m]
  float min_depth_m = 2.0f;         // ... and nearer ones (bonnet, image border) [m]
  float disparity_tol_px = 1.0f;    // |d - d_ground(v)| allowed with a ground model [px]
  float disparity_tol_rel = 0.05f;  // ... or this share of d_ground(v), whichever is larger
  float prior_cone_deg = 20.0f;     // ground normals must lie within this of -y [deg]
  int lower_margin_px = 10;         // without a ground model: rows > cy + this [px]
};

struct GroundSample {
  int u = 0, v = 0;
  cv::Vec3f n;  // unit normal (up)
  cv::Vec3f p;  // the pixel's 3D point [m]
  float d = 0;  // the pixel's disparity [px]
};

// The image rows that can hold ground samples ([0,0) when none can).
cv::Range groundRows(const StereoCamera& cam, const GroundModel& model,
                     const GroundSampleParams& params);

// Candidate test on the disparity alone (before the normal is computed).
bool isGroundCandidate(int v, float d, const StereoCamera& cam, const GroundModel& model,
                       const GroundSampleParams& params);

// Ground samples on the interval grid of `rows`; the field must cover them.
std::vector<GroundSample> selectGroundSamples(const IntegralNormalField& field,
                                              const cv::Mat& disparity, const StereoCamera& cam,
                                              const GroundModel& model,
                                              const GroundSampleParams& params, cv::Range rows,
                                              int interval_px);

}  // namespace nerv::snv
