// A surface just behind the top of a wide object. The height segmentation
// takes pixels within object_depth_tolerance_m (1.5 m) of a stixel as its
// own, and near misses up to top_near_miss_px farther as no mismatch. A truck
// 1.7 m behind a car (highway seed 31, frames 7-9, 21-23 m: car 18.1 px,
// truck 16.8 px) is within both, and over the truck's untextured rear the
// matcher reads 16.4-17.9 px (its vertical paths carry the car's disparity
// up), so half the car's strips run up the truck to its roof (tops at rows
// 117-150 against the car's 175) and the car's box is the truck's height.
// Seen over the whole object the rows above its strips' median top hold a
// second layer: most of their pixels in the group's columns sit at one
// disparity clearly farther than the group's. When they do, each strip whose
// top rises above the median top is segmented again from its foot with the
// two layers split halfway between them and no near misses; tops are only
// ever lowered. Narrow groups are left alone: over a far pedestrian the
// matcher reads the torso toward the background, which is no layer.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct LayerTopParams {
  float min_separation_m = 0.0f;   // the layer lies at least this much behind the group [m] (0 = off) ...
  float min_separation_px = 0.8f;  // ... and this many pixels of disparity ...
  float max_separation_px = 3.0f;  // ... and at most this many (pixels farther are background to the segmentation)
  float min_layer_share = 0.6f;    // share of the pixels above the median top nearer the layer than the group
  float min_width_m = 1.2f;        // groups at least this wide (vehicles) ...
  int min_rows = 3;                // ... whose highest top lies this many rows above the median top
  float ground_tolerance_m = 0.15f;// pixels this close to the road are road
};

// group: the stixels of one group; tops of those that ran up a layer behind
// are lowered. Returns how many stixels were lowered.
int lowerLayeredTops(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                     std::vector<Stixel*>& group, const LayerTopParams& p);

}  // namespace nerv::stixel
