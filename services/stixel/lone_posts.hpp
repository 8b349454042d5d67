// Lone posts in front of a far surface. A sign post at 15-25 m whose plate the
// height segmentation already reached (the post and plate are matched from the
// foot up) is one strip of the first layer: the grouping drops one-stixel groups,
// and the box left is the facade behind it (urban seed 12 frame 11: the post at
// 15.2 m in strip 370, rows 70-244, between the facade at 29 m and a stixel at
// 24 m). A first-layer stixel at least min_height_m tall whose first-layer
// neighbours within side_strips strips on each side all stand farther by at
// least min_gap_m and min_step_px (and that has at least one on each side) is
// returned as a post, to be kept when alone. Both sides, both thresholds: a
// strip of a tree or pole split off its own group has a neighbour at its
// depth (KITTI 0926 frame 3), a trunk in a row of trees at 30-50 m stands a
// fraction of a pixel in front of the next (highway seed 23).
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct LonePostParams {
  float min_height_m = 0.0f;    // stixels at least this tall are candidates (0 = off)
  float max_distance_m = 40.0f; // ... at most this far
  float min_gap_m = 5.0f;       // every neighbour is at least this much farther ...
  float min_step_px = 3.0f;     // ... and this many pixels of disparity below it
  int side_strips = 2;          // neighbours: first-layer stixels within this many strips on either side
};

// first_layer: the free space's stixels (one per strip at most), sorted by u.
// Returns copies of the lone posts found.
std::vector<Stixel> findLonePosts(const std::vector<Stixel>& first_layer, const StereoCamera& cam,
                                  const LonePostParams& p);

}  // namespace nerv::stixel
