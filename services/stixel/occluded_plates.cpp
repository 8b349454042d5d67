#include "occluded_plates.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"

namespace nerv::stixel {

std::vector<Stixel> placeOccludedPlates(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& g,
                                        const std::vector<Stixel>& first, std::vector<Stixel>& behind,
                                        const StixelExtractionParams& ep, const OccludedPlateParams& p) {
  std::vector<Stixel> posts;
  if (p.max_plate_top_m <= p.plate.min_plate_bottom_m || disparity.empty() || !g.valid) return posts;
  const double fb = cam.fx * cam.baseline_m;
  const float min_d = static_cast<float>(fb / std::min(p.max_distance_m, ep.free_space.max_distance_m));
  const float a = g.vd_slope, b = g.vd_intercept, h = g.height_m;
  // Row where a point of disparity d is height_m over the road.
  auto rowAt = [&](float d, float height_m) { return (d * (1.0f - height_m / h) - b) / a; };
  auto tolerancePx = [&](float d) { return disparityTolerance(d, cam, ep.object_depth_tolerance_m); };
  // The plate's height band as an "obstacle window" for medianObstacleDisparity.
  FreeSpaceParams band = ep.free_space;
  band.ground_tolerance_m = p.plate.min_plate_bottom_m;
  band.max_height_above_ground_m = p.max_plate_top_m;

  // Above an occluder a taller object beside the strip (a truck's box over its
  // cab) is no background: nearer pixels beside the plate count against it.
  SignPlateParams plate_test = p.plate;
  plate_test.nearer_beside = true;

  // Per row, the disparities whose pixels lie in the plates' height band.
  std::vector<float> band_lo, band_hi;
  obstacleDisparityWindow(g, disparity.rows, band.ground_tolerance_m, band.max_height_above_ground_m, band_lo, band_hi);

  std::vector<int> hist;
  std::vector<float> samples;
  for (const Stixel& s1 : first) {
    const int u0 = s1.u, u1 = std::min(disparity.cols, s1.u + s1.width);
    const int bottom = s1.top_row - 1;  // the occluder hides everything below its top
    if (bottom < 1 || u1 <= u0) continue;
    // A low occluder (a car, a hedge): a taller one is a truck, a tree or a post
    // itself, whose upper part is no plate behind it.
    if (heightAboveGround(g, static_cast<float>(s1.top_row), s1.disparity) > p.max_occluder_height_m) continue;
    // Farther than the occluder, nearer than the strip's second-layer stixel.
    const float d_hi = s1.disparity - tolerancePx(s1.disparity);
    auto second = std::find_if(behind.begin(), behind.end(), [&](const Stixel& s) { return s.u == s1.u; });
    // The second layer's surface lies clearly behind (a facade): a "plate" just
    // in front of it is that surface's own spread (a pole's mount, matcher noise).
    const float d_lo = second == behind.end()
                           ? min_d
                           : std::max({min_d, second->disparity + tolerancePx(second->disparity),
                                       static_cast<float>(fb / std::max(1.0f, second->depth_m - p.min_gap_m))});
    if (d_hi <= d_lo) continue;
    hist.assign(static_cast<size_t>(std::ceil(d_hi)) + 1, 0);
    // Rows where the band can hold a disparity in (d_lo, d_hi) (a height's row is
    // linear in d: its extremes are at the ends).
    const float top_m = band.max_height_above_ground_m, bottom_m = band.ground_tolerance_m;
    const int v_from = std::max(0, static_cast<int>(std::floor(std::min(rowAt(d_hi, top_m), rowAt(d_lo, top_m)))));
    const int v_to = std::min(bottom, static_cast<int>(std::ceil(std::max(rowAt(d_hi, bottom_m), rowAt(d_lo, bottom_m)))));
    for (int v = v_from; v <= v_to; ++v) {
      const float lo = std::max(d_lo, band_lo[static_cast<size_t>(v)]), hi = std::min(d_hi, band_hi[static_cast<size_t>(v)]);
      if (!(lo < hi)) continue;
      const float* row = disparity.ptr<float>(v);
      for (int u = u0; u < u1; ++u) {
        const float d = row[u];
        if (d > lo && d < hi) ++hist[static_cast<size_t>(d)];
      }
    }
    // Nearest first, as the free space and the second layer choose.
    const int k_end = static_cast<int>(hist.size());
    for (int k = k_end - 1; k >= static_cast<int>(d_lo); --k) {
      const int hw = obstacleHalfWindow(k);
      int n = 0;
      for (int j = std::max(0, k - hw); j <= std::min(k_end - 1, k + hw); ++j) n += hist[static_cast<size_t>(j)];
      const float z_k = static_cast<float>(fb / (k + 0.5));
      const float need = p.plate.min_row_fill * static_cast<float>(u1 - u0) *
                         std::max(2.0f, p.plate.min_plate_height_m * static_cast<float>(cam.fy) / z_k);
      if (static_cast<float>(n) < need) continue;
      const float lo = std::max(d_lo, static_cast<float>(k - hw)), hi = std::min(d_hi, static_cast<float>(k + hw + 1));
      const float d = medianObstacleDisparity(disparity, g, band, u0, u1, v_from, v_to, lo, hi, samples);
      if (d <= 0.0f) continue;
      const int lowest = std::min(bottom, static_cast<int>(std::floor(rowAt(d, p.plate.min_plate_bottom_m))));
      const int highest = static_cast<int>(std::ceil(rowAt(d, p.max_plate_top_m)));
      // Both sides must be seen: at the image's edge a wider object may go on.
      const int side = static_cast<int>(std::lround(p.plate.max_plate_width_m * cam.fx * d / fb));
      if (u0 - side - (u1 - u0) < 0 || u1 + side + (u1 - u0) > disparity.cols) continue;
      const PlateRows plate = findPlateRows(disparity, cam, u0, u1 - u0, d, lowest, highest, plate_test);
      // A "plate" running up to the search's top is a taller thing (a lamp post, a trunk).
      if (!plate.found() || !plate.closed) continue;
      Stixel st;
      st.u = u0;
      st.width = u1 - u0;
      st.top_row = plate.top;
      st.bottom_row = bottom;
      st.disparity = d;
      st.depth_m = static_cast<float>(fb / d);
      const int foot = std::clamp(static_cast<int>(std::lround((d - b) / a)), 0, disparity.rows - 1);
      const Point3 base = cam.toPoint(0.5 * (u0 + u1), foot, d);  // hidden foot: on the road line
      st.base_x_m = static_cast<float>(base.x);
      st.base_y_m = static_cast<float>(base.y);
      st.base_z_m = static_cast<float>(base.z);
      if (second != behind.end()) {
        *second = st;
      } else {
        behind.insert(std::lower_bound(behind.begin(), behind.end(), st,
                                       [](const Stixel& x, const Stixel& y) { return x.u < y.u; }),
                      st);
      }
      posts.push_back(st);
      break;
    }
  }
  return posts;
}

}  // namespace nerv::stixel
