// The background gap between a road user and a vehicle beside it. A cyclist
// riding along a parked row, or a pedestrian at the kerb, is 0.5-1.5 m beside
// a parked car at about its depth; the gap between them is 5-15 px wide at
// 30-40 m, about the matcher's window, so its strips read neither the
// background behind it nor either object but a blend between them, within
// the grouping's depth gap of both (urban seed 11, cyclist at 36 m: strips
// 10.6, 10.7 | gap 10.3, 10.2 | car 10.6 px, the background behind the gap 9 px).
// The gap chains the road user to the car, and on the box's edge the 1 px
// floor of the refinement's tolerance takes the car's columns in (boxes 9-21 px
// too wide on labels 12 px wide). On the rendered disparity the gap shows the
// background and the two stay apart. A group end of a road user's width and
// height, flat in disparity, next to one or two strips (at most max_gap_m)
// that are farther than it by at least min_dip_px and, where the group goes
// on, farther than the strip after them by min_dip_px too (a valley, not a
// ramp: a vehicle's receding side only recedes), is cut off there; the gap's
// strips belong to neither part and are dropped. An end standing on the road
// (not a vehicle's top seen above an occluder) needs only min_end_dip_px
// against it: at 33-37 m a parked car a car length behind a cyclist reads
// 0.35-0.5 px farther (urban seed 11, the car at 38.4 m beside the cyclist at
// 36.3 m); then a strip nearer than the gap strip before it ends the gap.
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct GapStripParams {
  float min_dip_px = 0.0f;     // the gap reads this much farther than both sides [px]; 0 = off ...
  float min_dip_m = 0.75f;     // ... and this much in depth [m] (near, a fraction of a px is centimetres)
  float min_end_dip_px = 0.0f; // against an end standing on the road, this dip instead [px] (0 = min_dip_px) ...
  float max_end_foot_gap_m = 0.3f; // ... its stixels' bottoms within this of the road [m]
  float max_gap_m = 0.6f;      // the gap's strips span at most this [m]
  float max_end_width_m = 1.0f; // the road user's end is at most this wide [m] ...
  float min_height_m = 1.4f;   // ... its median top at least this high over the road [m] ...
  float max_height_m = 2.2f;   // ... and at most this high ...
  float max_spread_px = 0.5f;  // ... and its stixels' disparities within this [px] ...
  int min_end_stixels = 2;     // ... and it keeps this many strips (a hypothesis' minimum)
};

// Columns [lo, hi) of a gap: stixels with u < lo form one part, u >= hi the
// other, the ones between are dropped. found = false: the group stays whole.
struct GapCut {
  bool found = false;
  int lo = 0, hi = 0;
};

// group: the stixels of one group, left to right (per strip the nearest counts).
GapCut findGapStrips(const std::vector<const Stixel*>& group, const StereoCamera& cam, const GroundModel* ground,
                     const GapStripParams& p);

}  // namespace nerv::stixel
