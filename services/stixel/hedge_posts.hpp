// A post standing in a short hedge. The tower rule (hypothesis_grouping)
// splits a post off when it is twice its group's median height; a striped
// post two strips wide in a hedge group of four strips is half the group, so
// the median is its own height and it stays in the hedge's box (KITTI 0926,
// the median hedge at 19-26 m: post 0.8-1 m visible, hedge strips 0.4-0.6 m).
// The local silhouette still tells: a narrow run of strips, post-tall, that
// stands clearly above the strips right beside it in the group.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct HedgePostParams {
  float min_ratio = 0.0f;      // the run's lowest stixel is this many times as tall as its taller neighbour; 0 = off
  float min_height_m = 0.8f;   // every stixel of the run is at least this tall (visible) [m]
  float min_step_m = 0.2f;     // the run's top stands this much above both neighbours' tops [m]
  float max_width_m = 0.45f;   // the run is at most this wide (a post, not a pedestrian or a car) [m]
  float max_distance_m = 30.0f; // farther runs stay (a post there is narrower than a strip) [m]
  bool at_group_end = false;    // a run at a group's end counts too when the rest of the group lies on its far side from the image centre column
};

// group: stixels of one group in u order, one per strip (a group holding two
// stixels in one strip, or touching the image's bottom row, is left alone).
// The run has group strips on both sides (a post inside the hedge) or, with
// at_group_end, is at one end of the group with the rest of the group farther
// from the image centre column cx than the run (a post at the hedge's end; a
// car's rear at a group's end has its lower receding side toward cx instead).
// Every stixel of the group outside the run must be min_ratio times lower
// than the run (the whole rest is hedge, not a vehicle). Returns the run [first, second) of the
// post, or {0, 0} when there is none.
std::pair<size_t, size_t> findHedgePost(const std::vector<const Stixel*>& group, const StereoCamera& cam,
                                        const HedgePostParams& p);

}  // namespace nerv::stixel
