// Low structures running along the road. A guard rail, a kerb wall or a low
// hedge beside the road is seen edge-on: its strips recede over many metres
// in depth and every one of them is low (highway seed 23 frame 4: the rail
// along the right edge, 0.6-0.8 m tall strips from 7.8 m to about 20 m, boxed
// as one "object" 8 m wide). Such a group is the road's border, not an
// obstacle in the road: it keeps its stixels (the free space ends there) but
// gives no hypothesis when
//  - it has at least min_stixels strips,
//  - they span at least min_depth_span_m in depth (nearest to farthest), and
//  - the 90th percentile of their visible heights is below max_height_m.
// A vehicle's side seen alongside recedes too, but its strips are as tall as
// the vehicle (1.4 m and more for a car); a pedestrian or a post spans no
// depth. docs/stixel.md "Low runs along the road".
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct LowRunParams {
  float max_height_m = 0.0f;      // 90th percentile strip height below this [m] ... (0 = off)
  float min_depth_span_m = 5.0f;  // ... over at least this depth range [m] ...
  int min_stixels = 4;            // ... and at least this many strips: the road's border, no hypothesis
};

// True when the group (stixels of one hypothesis) is such a low run.
bool isLowRun(const std::vector<const Stixel*>& group, const StereoCamera& cam, const LowRunParams& params);

}  // namespace nerv::stixel
