// A plain per-column stixel extractor: slow, simple and obviously correct, the
// baseline the fast path is checked and timed against (as libSGM's reference.h).
// Given the ground model, every pixel is lifted to 3D with StereoCamera::toPoint
// and its height over the road measured in the level frame; no occupancy grid,
// no dynamic programming, no precomputed row windows.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"
#include "stixel_estimator.hpp"

namespace nerv::stixel {

// For each strip: the nearest integer disparity whose obstacle pixels (within
// +-1 px) fill at least min_obstacle_height_m, their median disparity, the foot
// on the ground line, and the top as the highest row reached from the foot
// through rows holding a pixel of that depth with gaps of at most 3 rows.
std::vector<Stixel> referenceStixels(const cv::Mat& disparity, const StereoCamera& cam,
                                     const GroundModel& ground, const Params& params);

}  // namespace nerv::stixel
