// Obstacle hypotheses (ROIs): runs of neighbouring stixels at a similar depth.
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct GroupingParams {
  float group_depth_gap_m = 1.5f;      // neighbours farther apart in depth split a group
  float group_lateral_gap_m = 0.6f;    // neighbours farther apart sideways split a group
  int min_stixels_per_hypothesis = 2;  // smaller groups are dropped
  float min_obstacle_height_m = 0.25f; // lower groups are dropped
  float max_distance_m = 60.0f;        // farther groups are dropped
};

// stixels sorted by u (as extractStixels returns them). Hypotheses are numbered
// 0..n-1 from left to right.
std::vector<Hypothesis> groupStixels(const std::vector<Stixel>& stixels, const StereoCamera& cam,
                                     const GroupingParams& p);

}  // namespace nerv::stixel
