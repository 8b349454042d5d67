#include "occluded_stixels.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"
#include "obstacle_map.hpp"

namespace nerv::stixel {

std::vector<Stixel> extractOccludedStixels(const cv::Mat& disparity, const StereoCamera& cam,
                                           const GroundModel& g, const std::vector<Stixel>& first,
                                           const StixelExtractionParams& p) {
  return extractOccludedStixels(disparity, obstacleDisparityMap(disparity, g, p.free_space), cam, g, first, p);
}

std::vector<Stixel> extractOccludedStixels(const cv::Mat& disparity, const cv::Mat& obstacle_map,
                                           const StereoCamera& cam, const GroundModel& g,
                                           const std::vector<Stixel>& first, const StixelExtractionParams& p) {
  const FreeSpaceParams& fs = p.free_space;
  const double fb = cam.fx * cam.baseline_m;
  const float min_d = static_cast<float>(fb / fs.max_distance_m);

  std::vector<int> hist;
  std::vector<float> samples;
  std::vector<Stixel> out;
  for (const Stixel& s1 : first) {
    const int u0 = s1.u, u1 = std::min(disparity.cols, s1.u + s1.width);
    const int bottom = s1.top_row - 1;  // the occluder's top hides everything below
    if (bottom < 1) continue;
    // Clearly behind the first stixel: farther by its depth tolerance.
    const float tol1 = disparityTolerance(s1.disparity, cam, p.object_depth_tolerance_m);
    const float d_max = s1.disparity - tol1;
    if (d_max <= min_d) continue;
    hist.assign(static_cast<size_t>(std::ceil(d_max)) + 2, 0);
    for (int v = 0; v <= bottom; ++v) {
      const float* row = obstacle_map.ptr<float>(v);  // NaN off the obstacle heights
      for (int u = u0; u < u1; ++u) {
        const float d = row[u];
        if (d > min_d && d < d_max) ++hist[static_cast<size_t>(d)];
      }
    }
    // Mode over k +- obstacleHalfWindow(k), as the occupancy does.
    int best_k = -1, best_n = 0;
    for (int k = 0; k < static_cast<int>(hist.size()); ++k) {
      const int hw = obstacleHalfWindow(k);
      int n = 0;
      for (int j = std::max(0, k - hw); j <= std::min(static_cast<int>(hist.size()) - 1, k + hw); ++j) n += hist[j];
      if (n > best_n) best_n = n, best_k = k;
    }
    if (best_k < 0) continue;
    if (p.occluded_nearest) {
      // The nearest surface above the occluder that fills the minimum height
      // (what the free space picks for the first layer), not the most populous
      // one: the upper part of the next car in a parked row is seen in front of
      // the facade far behind it.
      auto windowed = [&](int k) {
        const int w = obstacleHalfWindow(k);
        int n = 0;
        for (int j = std::max(0, k - w); j <= std::min(static_cast<int>(hist.size()) - 1, k + w); ++j) n += hist[j];
        return n;
      };
      for (int k = static_cast<int>(hist.size()) - 1; k > best_k; --k) {
        const int n = windowed(k);
        if (n * fb / ((u1 - u0) * cam.fy * (k + 0.5)) < fs.min_obstacle_height_m) continue;
        // Centre the window on that surface: the fullest bin within one window below.
        int kk = k, nn = n;
        for (int j = k - 1; j >= std::max(0, k - 2 * obstacleHalfWindow(k)); --j)
          if (windowed(j) > nn) nn = windowed(j), kk = j;
        best_k = kk, best_n = nn;
        break;
      }
    }
    const int hw = obstacleHalfWindow(best_k);
    const float dlo = static_cast<float>(std::max(best_k - hw, 0)), dhi = static_cast<float>(best_k + hw + 1);
    // Filled height of the mode [m] must reach the minimum obstacle height.
    const float d_mode = best_k + 0.5f;
    const float filled_m = static_cast<float>(best_n * fb / ((u1 - u0) * cam.fy * d_mode));
    if (filled_m < fs.min_obstacle_height_m) continue;

    const float d = medianInRange(obstacle_map, u0, u1, 0, bottom, dlo, std::min(dhi, d_max), samples);
    if (d <= 0.0f) continue;
    Stixel st;
    if (stixelAtDisparity(disparity, cam, g, p, u0, u1, d, bottom, st)) out.push_back(st);
  }
  return out;
}

}  // namespace nerv::stixel
