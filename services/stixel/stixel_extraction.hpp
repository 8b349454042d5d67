// Stixels from the free-space boundary: a robust disparity per strip, its foot
// on the ground line and its top by height segmentation (Badino et al. 2009).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "free_space.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct StixelExtractionParams {
  FreeSpaceParams free_space;
  float object_depth_tolerance_m = 1.5f;  // pixels within this depth of the stixel belong to it
  float max_stixel_height_m = 10.0f;      // the top search stops this high over the road
  bool occluded_nearest = true;           // second layer: the nearest surface filling the minimum height, not the fullest
  float top_near_miss_px = 1.5f;          // top search: pixels up to this much farther than the tolerance are no mismatch; 0 = off
  float top_max_extension_m = 0.8f;       // ... which may raise the top by at most this much ...
  float top_min_resume_m = 0.05f;         // ... when rows this tall above the band are mostly at the stixel's disparity
};

// Top search of one strip: pixels within tolerance_px of the stixel's disparity
// match; see segmentTopRow for the near misses.
struct TopSearch {
  float tolerance_px = 1.0f;
  float near_miss_px = 0.0f;
  int max_extension_rows = 0;
  int min_resume_rows = 1;
};

// Top row by height segmentation. Scanning up from the foot, each pixel of the
// strip scores +1 when its disparity is within tolerance_px of the stixel's and it
// stands above the road tolerance, 0 when it is invalid or road, -1 otherwise
// (background or occluder); the top is the row maximising the summed score from the
// foot up (a maximum-subarray cut: a few mismatched rows do not end the obstacle,
// a background region does). The top may rise above the sky cut of the occupancy
// (trucks, poles are taller than it). Near misses: the matcher pulls a body
// narrower than its window (a far cyclist's torso) toward the background, so
// pixels farther than the tolerance by at most near_miss_px score 0 in a second
// sum; its argmax, at most max_extension_rows above the plain top, is the top
// when at least min_resume_rows rows between the two are mostly (more than half
// their valid pixels) at d: the head above a biased torso, not a surface just
// behind the object with a few stray matches above it.
// Median disparity of the obstacle pixels (between the road tolerance and the
// sky cut) of columns [u0, u1), rows [v0, v1], disparity in [lo, hi); 0 if none.
float medianObstacleDisparity(const cv::Mat& disparity, const GroundModel& ground, const FreeSpaceParams& fs,
                              int u0, int u1, int v0, int v1, float lo, float hi, std::vector<float>& scratch);

// The stixel of disparity d in columns [u0, u1): foot on the road line, visible
// from min(foot, max_bottom_row) up to the top found by segmentTopRow. False
// when its visible part is lower than the minimum obstacle height.
bool stixelAtDisparity(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                       const StixelExtractionParams& p, int u0, int u1, float d, int max_bottom_row, Stixel& out);

int segmentTopRow(const cv::Mat& disparity, const GroundModel& ground, float ground_tolerance_m,
                  int u0, int u1, int foot_row, int limit_row, float d, const TopSearch& search);

// boundary: bin per strip from solveFreeSpace (-1 = none).
std::vector<Stixel> extractStixels(const cv::Mat& disparity, const StereoCamera& cam,
                                   const GroundModel& ground, const std::vector<int>& boundary,
                                   const StixelExtractionParams& p);
// The same, given the frame's obstacleDisparityMap (obstacle_map.hpp) for p.free_space.
std::vector<Stixel> extractStixels(const cv::Mat& disparity, const cv::Mat& obstacle_map, const StereoCamera& cam,
                                   const GroundModel& ground, const std::vector<int>& boundary,
                                   const StixelExtractionParams& p);

}  // namespace nerv::stixel
