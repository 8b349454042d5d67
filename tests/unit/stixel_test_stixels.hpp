// Shared fixture of the grouping tests: a stixel built from a depth and a height,
// and the level road the scene renderer draws.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "ground_geometry.hpp"
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

// The road under a level camera camera_height_m above it (renderDisparity's
// default scene), as the v-disparity fit would give it.
inline GroundModel levelRoad(const StereoCamera& cam, double camera_height_m = 1.65) {
  const float slope = static_cast<float>(cam.baseline_m * cam.fx / (cam.fy * camera_height_m));
  return groundModelFromLine(slope, static_cast<float>(-slope * cam.cy), cam, "v_disparity");
}

// A stixel of strip u (5 px wide) at depth z standing on that road, its top
// top_m over it.
inline Stixel stixelOnRoad(const StereoCamera& cam, int u, double z, double top_m, double camera_height_m = 1.65) {
  Stixel s;
  s.u = u, s.width = 5;
  s.disparity = static_cast<float>(cam.disparityFromDepth(z));
  s.depth_m = static_cast<float>(z);
  s.bottom_row = static_cast<int>(std::lround(cam.cy + cam.fy * camera_height_m / z));
  s.top_row = static_cast<int>(std::lround(cam.cy + cam.fy * (camera_height_m - top_m) / z));
  return s;
}

// The post's hypothesis (a box taller than min_height_m within 1 m of depth z), if any.
inline std::optional<Hypothesis> postAt(const std::vector<Hypothesis>& hs, float z, float min_height_m = 2.0f) {
  for (const Hypothesis& h : hs)
    if (std::abs(h.z_m - z) < 1.0f && h.height_m > min_height_m) return h;
  return std::nullopt;
}

}  // namespace nerv::stixel
