// A car partly hidden behind a nearer one, widened to a car's width. In a
// parked row at 25-40 m the farther car's roof stands a pixel or two above
// the nearer car's (both roofs lie below the camera's 1.65 m), so no roof band
// shows over the occluder (occluded_sides.hpp finds none) and the box holds
// only the visible part: wet_road seed 7 frames 0-10, a car at 28-34 m whose
// box covers 0.6-1.3 m of its 1.8 m label beside a car 6-8 m nearer (IoU
// 0.33-0.49). A hypothesis min_width_m to max_width_m wide and min_height_m
// to max_height_m tall (a car's visible part, not a pedestrian, a van or a
// truck) whose one side is met by a nearer hypothesis - min_depth_step_m
// nearer, beginning within touch_px of that side and reaching beyond it,
// covering its bottom rows and at least half its height - is widened on that
// side to vehicle_width_m, never past the occluder's far edge. With occluders
// on both sides nothing changes (which side is hidden is unknown).
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct OccludedVehicleParams {
  float vehicle_width_m = 0.0f;   // a partly hidden car's box widened to this width [m] (0 = off) ...
  float min_width_m = 0.9f;       // ... when its box is at least this wide ...
  float max_width_m = 1.6f;       // ... and narrower than this ...
  float min_height_m = 1.2f;      // ... and between this ...
  float max_height_m = 1.9f;      // ... and this tall ...
  float min_depth_step_m = 2.0f;  // ... beside an occluder at least this much nearer ...
  int touch_px = 5;               // ... that begins within this many columns of its side
};

// Widens the boxes of `hs` in place (box, width_m and the base centre's x_m).
void widenOccludedVehicles(std::vector<Hypothesis>& hs, const StereoCamera& cam, const OccludedVehicleParams& p);

}  // namespace nerv::stixel
