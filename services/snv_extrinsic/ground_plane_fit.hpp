// Robust road plane on the ground points, fitted in disparity space.
//
// Why: the super-SNV pitch/roll (histogram -> mean shift over local normals)
// only sees disparity gradients over the normal window (<= 2 x 8 px), where
// SGBM's scanline aggregation flattens the gradient along the rows (the roll
// signal, measured 20 % low) and noise is large. The plane through the inlier
// ground points uses the whole road extent instead.
//
// Model: for a pinhole stereo camera every plane n . P = k is linear in
// disparity, d = a (u - cx) + b (v - cy) + c with (a fx, b fy, c) = (fB / k) n.
// The fit is done on (u, v, d): u, v are exact and SGBM's noise is additive in
// d, so least squares has no errors-in-variables bias (a fit of Y on (X, Z)
// would: the depth noise moves the regressors). Robust by IRLS with Tukey's
// biweight at tukey_k x 1.4826 MAD of the residuals; by default of the relative
// residuals (d - d_plane) / d, which is the height residual over the height
// (h_i = h d_plane / d), so a sidewalk 15 cm up is as far out near and far, and
// far samples, noisier in height, weigh less.
// Up normal n = -(a fx, b fy, c) / |.|, height = fB / |(a fx, b fy, c)|.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "stereo_camera.hpp"

namespace nerv::snv {

struct PlaneFitParams {
  int iterations = 6;            // IRLS iterations after the least-squares start
  float tukey_k = 4.685f;        // biweight cut-off in robust sigmas (95 % Gaussian efficiency)
  float min_sigma_px = 0.05f;    // floor of the robust residual sigma [px]
  bool relative = true;          // weights from residual / d (= height residual / h) instead of px
  float min_sigma_rel = 0.003f;  // floor of the relative sigma (0.5 cm at 1.65 m)
};

struct DisparityPlane {
  bool valid = false;
  double a = 0, b = 0, c = 0;   // d = a (u - cx) + b (v - cy) + c [px]
  float sigma_px = 0;           // robust residual sigma at the end [px]
  int inliers = 0;              // points with non-zero final weight
  double disparity(const StereoCamera& cam, double u, double v) const {
    return a * (u - cam.cx) + b * (v - cam.cy) + c;
  }
};

struct PlanePoint {
  float u, v, d;  // pixel and its (raw) disparity [px]
};

// Needs >= 3 points not on one line; else valid = false. `start`: the plane
// the IRLS begins from (weights from its residuals); without one, least squares
// over all points (which a raised sidewalk or a kerb can pull: give a start).
DisparityPlane fitDisparityPlane(const std::vector<PlanePoint>& points, const StereoCamera& cam,
                                 const PlaneFitParams& params,
                                 const DisparityPlane* start = nullptr);

// The disparity plane of the road with this up normal at height_m below the camera.
DisparityPlane planeFromNormal(const cv::Vec3f& up_normal, float height_m, const StereoCamera& cam);

// Unit road normal (pointing up, camera frame) and camera height [m] of a plane.
cv::Vec3f planeNormal(const DisparityPlane& plane, const StereoCamera& cam);
float planeHeightM(const DisparityPlane& plane, const StereoCamera& cam);

}  // namespace nerv::snv
