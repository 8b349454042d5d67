// Surface-normal needles for display, recomputed from a logged disparity map:
// SURFACE_NORMALS carries only per-ROI statistics, so the needle map is made
// here with a plain per-pixel cross product of 3D neighbour differences
//   N = (P(u+r,v) - P(u-r,v)) x (P(u,v+r) - P(u,v-r))
// on a box-smoothed disparity, and every needle is classed against the
// message's ground normal with the angles the snv stage uses (see
// services/snv_extrinsic/roi_normal_stats.hpp): ground within
// ground_tolerance_deg of g, upright (object) within 90 +- upright_tolerance_deg
// of g, facing (within facing_cone_deg of the camera's -z) is error-like unless
// it lies in a hypothesis the snv stage found upright-consistent.
// It is a picture of the same geometry, not the service's integral-image normals.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "stereo_camera.hpp"

namespace nerv::viz {

enum class NeedleClass { kGround, kObject, kError, kOther };

struct Needle {
  int u = 0, v = 0;     // pixel [px]
  cv::Vec3f p;          // 3D point [m], left camera frame (x right, y down, z forward)
  cv::Vec3f n;          // unit normal facing the camera
  NeedleClass cls = NeedleClass::kOther;
};

struct NeedleParams {
  int interval_px = 12;               // grid step of the needles [px]
  int radius_px = 4;                  // neighbour distance of the cross product [px]
  int smooth_px = 5;                  // box window over valid disparities before the product [px]
  float max_jump_rel = 0.08f;         // neighbour disparity differing more than this share: no normal
  float ground_tolerance_deg = 15.0f;
  float upright_tolerance_deg = 30.0f;
  float facing_cone_deg = 10.0f;
};

// Box mean of the valid disparities around each pixel (invalid where the
// centre is invalid), so one noisy pixel does not tip a needle.
cv::Mat smoothValidDisparity(const cv::Mat& disparity, int window_px);

// Class of unit normal n against unit ground normal g (both camera frame).
// `upright_roi`: the pixel lies in a hypothesis with upright support.
NeedleClass classifyNeedle(const cv::Vec3f& n, const cv::Vec3f& g, bool upright_roi,
                           const NeedleParams& params);

// Needles on the grid u % interval == 0, v % interval == 0 wherever the four
// neighbours are valid and continuous. upright_mask (CV_8U, may be empty):
// non-zero where a pixel is inside an upright-consistent hypothesis.
std::vector<Needle> computeNeedles(const cv::Mat& disparity, const StereoCamera& cam,
                                   const cv::Vec3f& ground_normal, const cv::Mat& upright_mask,
                                   const NeedleParams& params = {});

}  // namespace nerv::viz
