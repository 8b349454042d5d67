// A lower road user in front of a taller one, inside one group. A dark car
// 3 m in front of a truck (highway seed 31, 20-24 m) reads 18.2-19.4 px, the
// truck beside and above it 16.2-16.6 px, and a strip between them blends the
// two, so the grouping chains truck and car into one box with the truck's
// size: the truck is found, the car not (covered in 4 of 10 frames). Cutting
// the car out loses the truck instead (its left strips, the blended strip and
// its upper-layer stixels above the car fall apart; docs/detection_quality.md
// "A truck behind a car"). Here the group stays as it is and the front gets a
// box of its own as well. The group's first layer (the lowest stixel of each
// strip) is split at the widest gap of its disparities; when the gap is at
// least min_step_m and min_step_px, the longest run of neighbouring strips on
// its near side, min_height_m to max_height_m tall, whose top lies at least min_rise_m
// below the top of the rest of the group over the road, is the front.
#pragma once

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct NearerFrontParams {
  float min_step_m = 0.0f;     // the front is this much nearer than the far part (0 = off) ...
  float min_step_px = 0.8f;    // ... and this many pixels of disparity
  float max_height_m = 2.0f;   // the front is at most this tall (a car, a road user) ...
  float min_height_m = 1.2f;   // ... and its median strip at least this tall (not a bumper or a wheel of the far part) ...
  float min_rise_m = 1.0f;     // ... and the rest of the group rises this much higher over the road
  int min_strips = 2;          // the front spans at least this many strips
};

// group: the stixels of one hypothesis, left to right (several per strip).
// Returns the front's first-layer stixels, left to right, or nothing.
std::vector<const Stixel*> findNearerFront(const std::vector<const Stixel*>& group, const StereoCamera& cam,
                                           const GroundModel& ground, const NearerFrontParams& p);

}  // namespace nerv::stixel
