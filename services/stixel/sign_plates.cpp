#include "sign_plates.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"

namespace nerv::stixel {

namespace {

// Share of columns [u0, u1) of row v whose disparity is within tol of d (or, with
// nearer, above d - tol).
float rowShare(const cv::Mat& disparity, int v, int u0, int u1, float d, float tol, bool nearer = false) {
  u0 = std::max(u0, 0), u1 = std::min(u1, disparity.cols);
  if (u1 <= u0) return 0.0f;
  const float* row = disparity.ptr<float>(v);
  int n = 0;
  for (int u = u0; u < u1; ++u) n += std::abs(row[u] - d) <= tol || (nearer && row[u] > d) ? 1 : 0;
  return static_cast<float>(n) / static_cast<float>(u1 - u0);
}

}  // namespace

PlateRows findPlateRows(const cv::Mat& disparity, const StereoCamera& cam, int u, int width, float d, int lowest,
                        int highest, const SignPlateParams& p) {
  const double fb = cam.fx * cam.baseline_m;
  const double z = fb / d;
  const float tol = disparityTolerance(d, cam, p.depth_tolerance_m);
  const int side = static_cast<int>(std::lround(p.max_plate_width_m * cam.fx / z));
  const int need_rows = std::max(2, static_cast<int>(std::lround(p.min_plate_height_m * cam.fy / z)));
  lowest = std::min(lowest, disparity.rows - 1), highest = std::max(highest, 0);
  auto plateRow = [&](int v) {
    return rowShare(disparity, v, u, u + width, d, tol) >= p.min_row_fill &&
           rowShare(disparity, v, u - side - width, u - side, d, tol, p.nearer_beside) <= p.max_side_fill &&
           rowShare(disparity, v, u + width + side, u + 2 * width + side, d, tol, p.nearer_beside) <= p.max_side_fill;
  };
  // The lowest run of plate rows (one missing row bridged).
  int run_bottom = -1, run_top = -1, misses = 0;
  bool closed = false;
  for (int v = lowest; v >= highest; --v) {
    if (plateRow(v)) {
      if (run_bottom < 0) run_bottom = v;
      run_top = v, misses = 0;
    } else if (run_bottom >= 0 && ++misses > 1) {
      if (run_bottom - run_top + 1 >= need_rows) {
        // Closed: a plate's height of search rows above it, in which the strip
        // itself is mostly off the plate's depth (not a crown narrowing downwards).
        if (run_top - need_rows >= highest) {
          float share = 0;
          for (int r = run_top - need_rows; r < run_top; ++r) share += rowShare(disparity, r, u, u + width, d, tol);
          closed = share < p.min_row_fill * static_cast<float>(need_rows);
        }
        break;
      }
      run_bottom = run_top = -1, misses = 0;
    }
  }
  if (run_bottom < 0 || run_bottom - run_top + 1 < need_rows) return {};
  return {run_top, run_bottom, closed};
}

std::vector<Stixel> raiseToSignPlates(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& g,
                                      std::vector<Stixel>& stixels, const SignPlateParams& p) {
  std::vector<Stixel> raised;
  if (p.max_foot_height_m <= 0 || disparity.empty() || !g.valid) return raised;
  const float a = g.vd_slope, b = g.vd_intercept, h = g.height_m;
  // Row where a point of disparity d is height_m over the road.
  auto rowAt = [&](float d, float height_m) { return (d * (1.0f - height_m / h) - b) / a; };
  for (Stixel& s : stixels) {
    if ((s.bottom_row - s.top_row + 1) * s.depth_m / cam.fy > p.max_foot_height_m) continue;
    const float d = s.disparity;
    const int lowest = std::min(s.top_row - 1, static_cast<int>(std::floor(rowAt(d, p.min_plate_bottom_m))));
    const int highest = std::max(0, static_cast<int>(std::ceil(rowAt(d, p.max_plate_top_m))));
    const PlateRows plate = findPlateRows(disparity, cam, s.u, s.width, d, lowest, highest, p);
    if (!plate.found()) continue;
    s.top_row = plate.top;
    raised.push_back(s);
  }
  return raised;
}

}  // namespace nerv::stixel
