// Two pedestrians side by side. People walking or standing together are
// within the grouping's depth gap of each other and share one box, as wide
// as both and, since the row fill of the top then needs more than one head,
// lower than either. A group no wider than two people whose strips fall into
// two parts, each of a person's width and height and flat in disparity, with
// a clear disparity step between them (one stands a little behind the other),
// is cut at that step. A vehicle's rear is flat across its width (no step)
// and its side is a ramp (not flat), so neither is cut.
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct PersonPairParams {
  float min_step_px = 0.0f;      // disparity step between the two parts [px]; 0 = off ...
  float min_step_m = 0.3f;       // ... and in depth [m]
  float min_width_m = 0.3f;      // each part at least this wide [m] ...
  float max_width_m = 1.0f;      // ... and at most this wide
  float min_height_m = 1.4f;     // each part's median top this high over the road [m] ...
  float max_height_m = 2.2f;     // ... and at most this high
  float max_spread_px = 0.5f;    // each part's stixel disparities within this [px]
};

// group: the stixels of one group, left to right. Returns the column where
// the group is to be cut (stixels with u below it form the left part), or -1.
int findPersonPair(const std::vector<const Stixel*>& group, const StereoCamera& cam,
                   const GroundModel* ground, const PersonPairParams& p);

}  // namespace nerv::stixel
