// Second-layer stixels: objects seen above a nearer one. The free space
// gives one stixel per strip - the nearest obstacle - so a pedestrian
// standing behind a parked car, or the upper part of the next car in a
// parked row, has no stixel of its own. Above each first stixel's top, the
// strip's obstacle pixels (between the road tolerance and the sky cut) that
// lie clearly farther than it vote into a disparity histogram; a mode that
// fills at least the minimum obstacle height becomes a stixel whose visible
// bottom is the row above the occluder (its foot is hidden behind it).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"
#include "stixel_extraction.hpp"

namespace nerv::stixel {

// first: the stixels of extractStixels (one per strip at most, sorted by u).
// Returns the occluded stixels, sorted by u, at most one per first stixel.
std::vector<Stixel> extractOccludedStixels(const cv::Mat& disparity, const StereoCamera& cam,
                                           const GroundModel& ground, const std::vector<Stixel>& first,
                                           const StixelExtractionParams& p);
// The same, given the frame's obstacleDisparityMap (obstacle_map.hpp) for p.free_space.
std::vector<Stixel> extractOccludedStixels(const cv::Mat& disparity, const cv::Mat& obstacle_map,
                                           const StereoCamera& cam, const GroundModel& ground,
                                           const std::vector<Stixel>& first, const StixelExtractionParams& p);

}  // namespace nerv::stixel
