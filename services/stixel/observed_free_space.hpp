// Free or unseen? A strip without an obstacle reads as free up to the free
// space's range, but the matcher may have measured nothing there: glare, a
// wiper, dirt or rain on a lens, an untextured surface, or an object too near
// for the search range leave the disparity invalid, no obstacle evidence
// accumulates, and the boundary search returns "free" (a planner reading only
// the boxes would drive into the unseen). Here each strip gets the share of
// the pixels of its free space that carry a disparity: the image rows from
// the bottom up to the row where the road reaches the strip's free-space
// boundary (its nearest obstacle, or the free space's range when there is
// none). A strip whose share is below min_observed is unobserved: its free
// space is unknown, not free. Without a ground model nothing is free, and
// every strip is unobserved.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct ObservedParams {
  int column_width_px = 5;       // the free space's strips [px]
  float max_distance_m = 60.0f;  // a strip without an obstacle is free up to here [m]
  float min_observed = 0.3f;     // a strip with a smaller share of measured pixels is unobserved
};

// disparity: CV_32F (<= 0 or non-finite = invalid). boundary: solveFreeSpace's
// bin (= disparity, 1 px bins) per strip, -1 = free up to max_distance_m; empty
// or ground invalid: no free space, every strip unobserved. The result's
// ObservedFreeSpace is plain data (perception_types.hpp) for the message.
ObservedFreeSpace observeFreeSpace(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                                   const std::vector<int>& boundary, const ObservedParams& p);

}  // namespace nerv::stixel
