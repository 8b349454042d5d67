// The frame's obstacle pixels, classified once: a pixel is an obstacle when its
// height over the road lies between the road tolerance and the sky cut
// (heightAboveGround, the test the stixel extraction and the second layer make
// per pixel). Scans over a strip then compare disparities only.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "free_space.hpp"
#include "perception_types.hpp"

namespace nerv::stixel {

// CV_32F, the size of disparity: the disparity where the pixel is an obstacle
// (ground_tolerance_m < height < max_height_above_ground_m), NaN elsewhere (NaN
// fails every comparison, so a range test on the map is the test on the
// disparity and the height together).
cv::Mat obstacleDisparityMap(const cv::Mat& disparity, const GroundModel& ground, const FreeSpaceParams& fs);

// Median of the map's values in [lo, hi) over columns [u0, u1), rows [v0, v1]; 0 if none.
float medianInRange(const cv::Mat& obstacle_map, int u0, int u1, int v0, int v1, float lo, float hi,
                    std::vector<float>& scratch);

}  // namespace nerv::stixel
