// Free space: for every column strip, the disparity of the nearest obstacle
// standing on the road. Pixels are first sorted into road, sky and obstacle by
// their height over the ground; obstacle pixels vote into a column x disparity
// occupancy grid (the polar grid of Badino et al. 2009, "The Stixel World");
// dynamic programming across strips then picks one boundary per strip that
// balances evidence against smoothness.
#pragma once

#include <opencv2/core.hpp>

#include <limits>
#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct FreeSpaceParams {
  int column_width_px = 5;
  float ground_tolerance_m = 0.15f;       // below this height a pixel is road
  float max_height_above_ground_m = 2.5f; // above this height a pixel is sky
  float min_obstacle_height_m = 0.25f;    // occupied height an obstacle needs
  float max_distance_m = 60.0f;           // farther obstacles are ignored
  float max_disparity_px = 256.0f;        // disparities at or above are invalid
  float smoothness_m = 0.05f;             // DP cost per disparity bin of boundary jump [m]
  int jump_cap_bins = 4;                  // a jump costs at most this many bins (object edges)
  float max_clearance_m = 0.0f;           // evidence whose lowest pixel is higher over the road floats
                                          // (a tree crown over the sidewalk): none; 0 = off
};

// Column strip s x disparity bin k (1 px) of obstacle pixels, in metres:
//  - filled_m: how much height the pixels fill (count / width rows, times metres per row);
//    holes of the matcher make it an underestimate;
//  - reach_m / base_m: height over the road of the cell's highest / lowest pixel.
//    A flat patch above the road tolerance (kerb, raised lawn, a road that is not
//    quite the fitted plane) fills many cells a little and all its pixels sit at
//    about one height; an upright obstacle fills and spans a height range.
struct OccupancyGrid {
  int strips = 0, bins = 0;
  int column_width_px = 0;
  int min_bin = 0;                 // bins below (beyond max_distance_m) are not used
  int end_bin = 0;                 // one past the highest bin holding a pixel
  std::vector<float> filled_m;     // strips x bins
  std::vector<float> reach_m;      // strips x bins
  std::vector<float> base_m;       // strips x bins
  float max_clearance_m = std::numeric_limits<float>::infinity();  // see FreeSpaceParams
  size_t index(int s, int k) const { return static_cast<size_t>(s) * bins + k; }
};

// Obstacle evidence [m] of strip s at bin k: over the bins k +- obstacleHalfWindow(k),
// min(total filled height, highest reach - lowest base) -- it must both be dense
// and stand upright. Evidence that does not come down to max_clearance_m over
// the road is none: it hangs over the road or sidewalk (a tree crown, a
// bridge), and a free-space boundary there would hide what stands below it.
float obstacleScore(const OccupancyGrid& grid, int s, int k);

// Row-wise disparity window [lo, hi] in which a pixel is an obstacle
// (ground_tolerance_m < height < max_height_above_ground_m); empty when lo >= hi.
void obstacleDisparityWindow(const GroundModel& g, int rows, float ground_tolerance_m,
                             float max_height_m, std::vector<float>& lo, std::vector<float>& hi);

OccupancyGrid buildOccupancy(const cv::Mat& disparity, const StereoCamera& cam,
                             const GroundModel& ground, const FreeSpaceParams& p);

// Half width (bins) of the disparity window an obstacle at bin k spreads over.
int obstacleHalfWindow(int k);

// Boundary bin per strip (-1: free up to max_distance_m).
std::vector<int> solveFreeSpace(const OccupancyGrid& grid, const FreeSpaceParams& p);

}  // namespace nerv::stixel
