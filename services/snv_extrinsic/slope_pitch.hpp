// Camera pitch from the ground samples' normalised vertical disparity slopes:
// an estimator whose residual is linear in the disparity noise (issue 6).
//
// Why: the per-normal pitch tan(theta_i) = S/(fy dS/dv) - (v - cy)/fy divides by
// the box-mean disparity difference over 2r rows (2-4 px, noise ~0.15-0.2 px), so
// its distribution is skewed (SGBM: median +0.72 deg, p75 +3.9 deg) and the mean
// shift on it is biased (docs/snv.md, pitch_oscillation).
//
// What a normal carries: with the disparity box-smoothed (integral_normals.hpp,
// smooth_disparity), the normal N = t x h is normal to every disparity plane
// d = a (u-cx) + b (v-cy) + c that is parallel to both tangents, which gives
//   beta = b / d(u, v) = (S_d - S_u) / (2r (S_d + S_u) / 2) = n_y / (fy (n . ray)),
// ray = ((u-cx)/fx, (v-cy)/fy, 1): the window's vertical disparity slope over its
// disparity [1/px], linear in the box-mean noise (the mean disparity in the
// denominator has ~1 % of that relative noise).
//
// Model: the road with up normal n(theta, phi) (normalFromPitchRoll) has
// beta(theta; u, v) = n_y / (fy (n . ray)) at every pixel (for phi = 0:
// 1 / (v - v_horizon), v_horizon = cy - fy tan theta). Each sample is linearised
// around the current pitch: theta_i = theta + (beta_i - beta(theta; u_i, v_i)) /
// (d beta / d theta), a per-sample pitch whose noise is symmetric (no division by
// a noisy quantity); the robust location of the theta_i (Tukey biweight, or the
// adaptive mean shift) is the next pitch; repeat until it moves < stop_deg. On
// exact disparity this is Newton's method on an exact model (0 error).
// Roll phi is held fixed (the road plane's, ground_plane_fit.hpp).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "stereo_camera.hpp"

namespace nerv::snv {

struct SlopeSample {
  float u = 0, v = 0;  // pixel
  float beta = 0;      // normalised vertical disparity slope (dd/dv) / d [1/px]
};

// The normalised vertical slope carried by a ground normal at pixel (u, v)
// (see above); NaN when n . ray == 0.
float normalisedVerticalSlope(const cv::Vec3f& up_normal, float u, float v, const StereoCamera& cam);

// beta of the road with this pitch and roll at pixel (u, v).
double roadNormalisedSlope(float pitch_deg, float roll_deg, double u, double v, const StereoCamera& cam);

struct SlopePitchParams {
  int iterations = 20;          // outer (re-linearisation) iterations at most
  float stop_deg = 1e-3f;       // stop when the pitch moves less than this [deg]
  bool mean_shift = false;      // location: adaptive mean shift (fraction below) instead of Tukey
  float fraction = 0.5f;        // mean-shift window share
  float tukey_k = 4.685f;       // Tukey cut-off in robust sigmas (1.4826 MAD of theta_i - theta)
  float min_sigma_deg = 0.01f;  // floor of that sigma [deg]
};

struct SlopePitchResult {
  bool valid = false;
  float pitch_deg = 0;
  float sigma_deg = 0;   // robust spread of the linearised per-sample pitches [deg]
  int inliers = 0;       // samples with non-zero weight (Tukey) / in the window (mean shift)
  int iterations = 0;
};

// Needs >= 3 samples; starts at start_pitch_deg (e.g. the super-SNV mean shift).
SlopePitchResult fitSlopePitch(const std::vector<SlopeSample>& samples, const StereoCamera& cam,
                               float roll_deg, float start_pitch_deg, const SlopePitchParams& params);

// The linearised per-sample pitches theta_i around pitch_deg (exposed for tests
// and for the histogram of the transformed variable).
void linearisedPitchesDeg(const std::vector<SlopeSample>& samples, const StereoCamera& cam,
                          float roll_deg, float pitch_deg, std::vector<float>& out);

}  // namespace nerv::snv
