// Plain data exchanged between the algorithms of the stages (no transport).
// The LCM messages in lcmtypes/ carry the same fields; common/message_convert
// turns one into the other.
#pragma once

#include <string>
#include <vector>

namespace nerv {

// Road model used by a stixel frame. Pitch positive = camera looks down.
struct GroundModel {
  bool valid = false;
  std::string source = "none";   // "v_disparity" | "extrinsics_prior" | "none"
  float vd_slope = 0;            // ground disparity d = vd_slope * v + vd_intercept
  float vd_intercept = 0;
  float horizon_row = 0;         // row where the ground disparity is 0 [px]
  float pitch_deg = 0;
  float roll_deg = 0;
  float height_m = 0;
  int inliers = 0;
  float residual_px = 0;
  // Disparity the ground has at row v (may be <= 0 above the horizon).
  float groundDisparity(float v) const { return vd_slope * v + vd_intercept; }
};

struct Stixel {
  int u = 0, width = 0;          // left column and width [px]
  int top_row = 0;               // first obstacle row [px]
  int bottom_row = 0;            // foot point row [px]
  float disparity = 0;           // [px]
  float depth_m = 0;
  float base_x_m = 0, base_y_m = 0, base_z_m = 0;
};

struct Box {
  int x = 0, y = 0, w = 0, h = 0;  // [px]
};

// How much of each free-space strip was measured (stixel::observeFreeSpace):
// a strip below min_observed is unknown, not free. num columns 0 = not computed.
struct ObservedFreeSpace {
  int column_width_px = 0;
  std::vector<float> observed;   // per strip, 0..1: share of its free-space pixels with a disparity
  float min_observed = 0.0f;     // the threshold num_unobserved counts against
  float observed_share = 0.0f;   // the same share over every strip's free-space pixels
  int num_unobserved = 0;        // strips below min_observed
};

// An obstacle hypothesis (ROI).
struct Hypothesis {
  int id = 0;
  Box box;
  float x_m = 0, y_m = 0, z_m = 0;  // base centre, left camera frame [m]
  float width_m = 0, height_m = 0, distance_m = 0;
  float nearest_z_m = 0;            // depth of the nearest part (90th percentile of the stixels' disparities) [m]
  float nearest_z_sigma_m = 0;      // 1-sigma uncertainty of nearest_z_m (stixel depth_sigma_px) [m]
  float disparity = 0;
  int num_stixels = 0;
};

// Normal statistics of one hypothesis (see normal_stats_t.lcm for the meaning).
struct NormalStats {
  int roi_id = 0;
  int num_samples = 0;
  int num_normals = 0;
  float density = 0;
  float ground_fraction = 0;
  float object_fraction = 0;
  float error_fraction = 0;
  float normal[3] = {0, 0, 0};
  float pitch_deg = 0;
  float yaw_deg = 0;
  float tilt_from_ground_deg = 0;
};

// Camera pose against the road as estimated from surface normals.
struct PoseEstimate {
  bool valid = false;
  std::string status = "no_ground";
  float pitch_deg = 0, roll_deg = 0, height_m = 0;              // filtered
  float instant_pitch_deg = 0, instant_roll_deg = 0, instant_height_m = 0;
  float pitch_mode_deg = 0, pitch_mean_deg = 0, pitch_mean_shift_deg = 0;
  float entropy = 0, confidence = 0;
  int num_normals = 0, inliers = 0;
  float filter_pitch_var = 0;
};

struct Verdict {
  int roi_id = 0;
  std::string label = "unvalidated";  // "object" | "ground" | "error" | "unvalidated"
  float score = 0;
  bool kept = false;
  std::string reason;                 // empty when kept
};

}  // namespace nerv
