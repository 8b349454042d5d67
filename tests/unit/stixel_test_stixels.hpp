// Shared fixture of the grouping tests: a stixel built from a depth and a height.
#pragma once

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

// A stixel of strip u (5 px wide) standing on bottom_row (no ground: heights are visible heights).
inline Stixel stixelAt(const StereoCamera& cam, int u, float z, float height_m, int bottom_row = 240) {
  Stixel s;
  s.u = u, s.width = 5, s.depth_m = z;
  s.disparity = static_cast<float>(cam.disparityFromDepth(z));
  s.bottom_row = bottom_row;
  s.top_row = bottom_row - static_cast<int>(height_m * cam.fy / z);
  return s;
}

}  // namespace nerv::stixel
