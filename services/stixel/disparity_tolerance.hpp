// Disparity span of a depth span. Depth z = fB/d, so dz = z^2/(fB) dd and a
// depth tolerance of `metres` at disparity d is d^2 * metres / (fB) pixels -
// floored at 1 px, the matcher's resolution (beyond ~20 m for 1 m the floor
// decides). Every stixel rule that asks "is this pixel at that object's
// depth" uses this one band.
#pragma once

#include <algorithm>

#include "stereo_camera.hpp"

namespace nerv::stixel {

inline float disparityTolerance(float d, const StereoCamera& cam, float metres) {
  const double fb = cam.fx * cam.baseline_m;
  return std::max(1.0f, static_cast<float>(d * d * metres / fb));
}

}  // namespace nerv::stixel
