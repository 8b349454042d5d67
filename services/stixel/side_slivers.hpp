// Slivers of a vehicle's receding side. Beyond ~15 m the side of a vehicle
// seen at a grazing angle recedes by metres per strip, and its last strips -
// the side's far end and the matcher's smear just past it, or the band where
// a nearer vehicle's edge overlaps a farther one - read 1-9 m behind the
// vehicle's rear, beyond the grouping's depth gap. They become a narrow box
// of their own beside the vehicle's (wet_road seed 5 frame 19: a van at 17 m,
// strips at 16.5-19.7 m, then three at 21.4-21.5 m, the side's front corner and
// the smear beyond it; frames 15-21 the same, highway seed 23 a truck's side
// at 25-30 m beside its rear at 19-22 m). joinSides (hypothesis_grouping.cpp)
// takes such a side only when it recedes strictly and continues the body's
// top row; on these the depths are flat within noise (21.44, 21.36, 21.49)
// and the tops fall short. A small group is a sliver of the vehicle it
// touches when
//  - it is at most max_stixels strips and max_width_m wide, and the vehicle
//    at least min_host_width_m wide, wider than it, its median stixel top
//    min_host_height_m to max_host_height_m over the road (a vehicle, not a
//    hedge or a facade);
//  - it lies towards the principal point from the vehicle, sticks out beyond
//    the vehicle's edge there and touches it, at most one empty strip
//    between (a side projects towards the vanishing point as it recedes; a
//    "sliver" on the outward side is another object);
//  - it is farther than the vehicle's facing stixel, and its far end at most
//    max(max_depth_m, length_per_height x h) behind the vehicle's nearest
//    stixel, h the larger of the facing stixel's height and the vehicle's
//    visible height (a vehicle's length: the next car of a row, seen beyond a
//    gap, stays apart; a truck's edge strip may stand 1.8 m tall of 3.6);
//  - its top stands no higher over the road than the vehicle's median
//    stixel top or its facing stixel's top, whichever is higher, plus
//    top_tolerance_m: a pedestrian or cyclist beside a car is taller than the
//    car (the rule height_steps.hpp cuts them by), a side is not taller than
//    its own vehicle (wet_road seed 5 frame 19: the van's median top 2.15 m,
//    lowered by its low left strips, its rear corner 2.25 m, the sliver 2.26 m).
//  Beside a vehicle whose median top stands at least tall_host_m (a truck or
//  a bus: taller than any road user) with a flat roof line (its stixel tops'
//  interquartile range at most tall_max_top_spread_m; a tree or a sign group
//  is ragged) the top margin is tall_top_tolerance_m, up to
//  tall_max_gap_strips empty strips may lie between, and the sliver may be
//  tall_max_stixels strips and tall_max_width_m wide (a truck's side at 25-30 m
//  spans 5-6 strips and 1.0-1.2 m; beside a 3 m tree group at 43 m those sizes
//  folded a pedestrian at 32 m, urban seed 13 frame 0, before the flatness test): highway seed 31
//  frame 10, a truck's side at 29-32 m two empty strips left of its rear at
//  22 m (the side's first metres blend with the rear's edge), its far end,
//  read at its strips' median depth on a ramp, 3.75 m over the road beside
//  the rear's 3.51 m (truth 3.54 m). Beside a 2.1 m van, two strips folded a
//  cyclist 5.6 m behind it (urban seed 13 frame 15, rendered disparity).
// A sliver at least min_fold_share of the vehicle's visible height is its
// side and widens its box (highway seed 23: the cars' boxes ended 8-14 px
// short of their labels); a lower one is the matcher's smear beside the
// vehicle's lower part and is dropped (wet_road seed 7 frames 4-6: 0.6 m
// pieces beside a van's bottom, 10 px beyond its label).
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct SideSliverParams {
  int max_stixels = 0;             // a group of at most this many strips ... (0 = off)
  float max_width_m = 0.9f;        // ... and at most this wide [m] ...
  float min_host_width_m = 1.2f;   // ... beside a vehicle at least this wide [m] ...
  float min_host_height_m = 1.0f;  // ... whose median stixel top stands at least this high over the road ...
  float max_host_height_m = 4.5f;  // ... and at most this high (not a hedge, a facade or a tree) ...
  float max_depth_m = 6.0f;        // ... ending at most this far behind its nearest stixel [m] ...
  float length_per_height = 3.0f;  // ... or this many times its facing stixel's height (trucks) ...
  float top_tolerance_m = 0.1f;    // ... and no higher over the road than its median or facing top + this [m] is its sliver
  float tall_host_m = 0.0f;        // beside a vehicle whose median top reaches this [m] (0 = none) ...
  float tall_top_tolerance_m = 0.5f; // ... the top may stand this much higher instead [m]
  int tall_max_gap_strips = 2;     // ... and at most this many empty strips may lie between (else one) ...
  int tall_max_stixels = 6;        // ... and the sliver may be this many strips ...
  float tall_max_width_m = 1.5f;   // ... and this wide [m] ...
  float tall_max_top_spread_m = 0.4f; // ... when the tall vehicle's tops lie within this (interquartile) [m]
  float min_fold_share = 0.5f;     // a sliver this share of the vehicle's visible height folds into it, a lower one is dropped
  int column_width_px = 5;         // stixel strip width
};

enum class SliverAction { kNone, kFold, kDrop };

// sliver, host: the stixels of two groups, left to right (both layers; per
// strip the nearest one counts). kFold or kDrop when `sliver` is a sliver of
// `host`'s side by the tests above, kNone otherwise. ground: for the tops over
// the road (without one, the stixels' visible heights).
SliverAction sliverAction(const std::vector<const Stixel*>& sliver, const std::vector<const Stixel*>& host,
                          const StereoCamera& cam, const GroundModel* ground, const SideSliverParams& p);

}  // namespace nerv::stixel
