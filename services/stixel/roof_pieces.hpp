// Pieces stacked on a vehicle's roof line. Above a car's rear the matcher
// reads the rear window, the roof and the background seen over it a few
// metres farther than the rear; those rows become upper-layer stixels on top
// of the car's, beyond the grouping's depth gap, and a thin strip of them a
// box of its own inside the car's (kitti_raw_0926_seq frame 6: a car at
// 25.2-25.6 m, u 335-410, its three strips at u 360-375 topped by stixels at
// 27.4-27.7 m, rows 188-195 over the car's 196; frame 7 the same, 28.6-29.7 m
// over a car at 25.6 m). A small group is such a piece of the vehicle it sits
// on when
//  - it is at most max_stixels strips, and the vehicle at least
//    min_host_width_m wide, with more strips, its median stixel top
//    min_host_height_m to max_host_height_m over the road (a vehicle, not a
//    hedge or a facade: a post in front of a hedge stands on the road, not on
//    the hedge's top);
//  - every stixel of it stands on a stixel of the vehicle in its strip: its
//    bottom row within max_gap_px of the row above that stixel's top, and it
//    is farther, by at most max_depth_m (a car's length);
//  - its top is no higher than the vehicle's highest stixel top plus
//    top_tolerance_px: it lies inside the vehicle's box. A road user behind a
//    car seen over its roof is taller than the car and sticks out above it.
// Such a piece adds nothing to the vehicle's box and is dropped.
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct RoofPieceParams {
  int max_stixels = 0;             // a group of at most this many strips ... (0 = off)
  float min_host_width_m = 1.2f;   // ... on a vehicle at least this wide [m] ...
  float min_host_height_m = 1.0f;  // ... whose median stixel top stands at least this high over the road ...
  float max_host_height_m = 4.5f;  // ... and at most this high ...
  int max_gap_px = 2;              // ... each stixel's bottom within this of the row above the vehicle's stixel top [px] ...
  float max_depth_m = 6.0f;        // ... and farther than it by at most this [m] ...
  int top_tolerance_px = 1;        // ... with its top no higher than the vehicle's highest top + this [px] is a piece of it
};

// piece, host: the stixels of two groups, left to right (both layers). True
// when `piece` stands on `host`'s roof line by the tests above. ground: for the
// host's tops over the road (without one, the stixels' visible heights).
bool isRoofPiece(const std::vector<const Stixel*>& piece, const std::vector<const Stixel*>& host,
                 const StereoCamera& cam, const GroundModel* ground, const RoofPieceParams& p);

}  // namespace nerv::stixel
