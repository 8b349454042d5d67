// Road users beside a vehicle at its depth. A cyclist seen from behind in the
// lane, or a pedestrian at the kerb, next to a parked car stands within the
// grouping's depth gap of it (beyond ~30 m the difference of 1-3 m is below
// one disparity step), so both become one box, as wide as both and as high
// as the car's roof fills it. What still tells them apart in the disparity is
// their height: a cyclist or pedestrian is 1.6-1.9 m tall, a car 1.4-1.5 m.
// A group whose strips at one end, no wider than a road user, stand at least
// min_step_m above the strips next to them and above the rest of the group
// (median), and are themselves of a person's height, is cut there: the end
// becomes a hypothesis of its own, and its box is kept off the rest's columns.
// Nearer than ~30 m the matcher often loses the top of a head, so the height
// step shrinks below noise; there the depth still tells: an end flat in
// disparity and nearer than its two neighbours by min_depth_step_m (and
// min_depth_step_px) is cut as well (the grouping's 1.5 m gap joined them).
// Only nearer ends: a vehicle's receding side is a narrow end farther than
// its neighbours.
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct HeightStepParams {
  float min_step_m = 0.0f;          // the end stands this much above the rest [m]; 0 = off
  float max_width_m = 1.0f;         // the end is at most this wide (a cyclist or a pedestrian) [m]
  float min_height_m = 1.5f;        // its median stixel is at least this tall [m] ...
  float max_height_m = 2.2f;        // ... and at most this (taller: a van's body, a post, a tree)
  int min_rest_stixels = 2;         // the lower part keeps at least this many strips ...
  float min_rest_width_m = 0.7f;    // ... and this width [m] (a vehicle, not a pedestrian's shoulder)
  float max_distance_m = 1e9f;      // farther groups stay whole (there one disparity step is metres)
  float min_depth_step_m = 0.0f;    // or: a flat end nearer than its two neighbours by this [m] (0 = off) ...
  float min_depth_step_px = 0.8f;   // ... and this many px (above the stixels' disparity noise) ...
  float max_end_spread_px = 0.5f;   // ... flat: its stixels' disparities within this [px] ...
  float depth_step_min_height_m = 1.5f; // ... and at least this tall (up to max_height_m)
};

// Height of a stixel's top over the road [m] (without a ground: its visible height).
float topHeightOverRoad(const Stixel& s, const StereoCamera& cam, const GroundModel* ground);

// group: the stixels of one group, left to right (both layers; per strip the
// nearest one counts). Heights are those of the stixel tops over the road
// (ground's line; without a ground, the stixels' visible heights). Returns the
// column where the group is to be cut (stixels with u below it form the left
// part), or -1 when it stays whole.
int findHeightStep(const std::vector<const Stixel*>& group, const StereoCamera& cam,
                   const GroundModel* ground, const HeightStepParams& p);

}  // namespace nerv::stixel
