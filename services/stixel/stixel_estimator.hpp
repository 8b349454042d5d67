// Disparity -> ground model (v-disparity), cleanup, stixels and obstacle
// hypotheses. The "stixel only" detector of the NERV reference (slides 3, 10).
// No transport here: services/stixel/main.cpp wires it to LCM.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "config.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct Params {
  int column_width_px = 5;               // stixel width [px]
  float max_height_above_ground_m = 2.5f;// pixels higher than this above the road are "sky"
  float ground_tolerance_m = 0.15f;      // pixels closer than this to the road plane are road
  float min_obstacle_height_m = 0.25f;   // shorter stixels are dropped
  float max_distance_m = 60.0f;          // hypotheses farther away are dropped
  float min_camera_height_m = 0.5f;      // ground lines implying another height are rejected
  float max_camera_height_m = 4.0f;
  float max_pitch_deg = 10.0f;           // ground lines implying a steeper pitch are rejected
  float group_depth_gap_m = 1.5f;        // neighbouring stixels farther apart in depth split a box
  float group_lateral_gap_m = 0.6f;      // neighbouring stixels farther apart sideways split a box
  int min_stixels_per_hypothesis = 2;    // smaller groups are dropped
  bool use_extrinsics_prior = true;      // fall back to the latest EXTRINSICS when the fit is weak
};

// Reads the `stixel:` section of a pipeline config into Params (ConfigError on bad keys).
Params readParams(ConfigSection& section);

// Camera pose from snv_extrinsic used when the v-disparity fit is weak.
struct GroundPrior {
  bool valid = false;
  float pitch_deg = 0, roll_deg = 0, height_m = 0;
};

struct StixelResult {
  GroundModel ground;
  std::vector<Stixel> stixels;
  std::vector<Hypothesis> hypotheses;
};

// disparity: CV_32F, left view, <= 0 or non-finite = invalid; cam must match its size.
StixelResult estimateStixels(const cv::Mat& disparity, const StereoCamera& cam,
                             const Params& params, const GroundPrior& prior = {});

}  // namespace nerv::stixel
