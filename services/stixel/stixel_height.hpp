// Visible metric height of a stixel: its rows (top to foot, both included) at its depth.
#pragma once

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

inline float stixelHeightM(const Stixel& s, const StereoCamera& cam) {
  return static_cast<float>((s.bottom_row - s.top_row + 1) * s.depth_m / cam.fy);
}

}  // namespace nerv::stixel
