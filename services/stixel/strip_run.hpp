// A run of neighbouring strips read as one part of a group (a road user's end
// of it, one of two pedestrians): its width, median top over the road, median
// disparity and disparity spread, the figures the cutting rules test.
#pragma once

#include <cstddef>
#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct StripRun {
  float width_m = 0;    // from the first strip's left to the last strip's right edge, at the first's depth
  float median_h = 0;   // median top over the road [m] (topHeightOverRoad)
  float median_d = 0;   // median disparity [px]
  float spread_px = 0;  // largest minus smallest disparity [px]
};

// s: one stixel per strip, left to right; the run is s[a, b), a < b.
StripRun describeRun(const std::vector<const Stixel*>& s, size_t a, size_t b, const StereoCamera& cam,
                     const GroundModel* ground);

}  // namespace nerv::stixel
