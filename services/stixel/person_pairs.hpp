// Two pedestrians side by side. People walking or standing together are
// within the grouping's depth gap of each other and share one box, as wide
// as both and, since the row fill of the top then needs more than one head,
// lower than either. A group no wider than two people whose strips fall into
// two parts, each of a person's width and height and flat in disparity, with
// a clear disparity step between them (one stands a little behind the other),
// is cut at that step. A vehicle's rear is flat across its width (no step)
// and its side is a ramp (not flat), so neither is cut. Where the matcher
// blends the two over the strip between them (urban seed 12 frame 5: 24.6-
// 25.0 px | 25.5 | 26.1-26.4 at 15 m), up to max_blend_strips strips reading
// between the parts' disparities belong to neither and are dropped, when
// each part spans at least min_blend_part_strips: at 30 m a person is two or
// three strips, and an occluded car's receding side and rear read the same.
#pragma once

#include <vector>

#include "gap_strips.hpp"
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
  int max_blend_strips = 0;      // strips between the parts reading between them (the matcher's blend), dropped ...
  int min_blend_part_strips = 3; // ... when each part spans at least this many strips (farther, a blend is a ramp's step)
};

// group: the stixels of one group, left to right. Returns the columns [lo, hi)
// of the cut (stixels with u below lo form the left part, from hi on the
// right; lo == hi without a blended strip); found = false: no cut.
GapCut findPersonPair(const std::vector<const Stixel*>& group, const StereoCamera& cam, const GroundModel* ground,
                      const PersonPairParams& p);

}  // namespace nerv::stixel
