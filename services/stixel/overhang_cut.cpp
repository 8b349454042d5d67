#include "overhang_cut.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"

namespace nerv::stixel {

int cutOverhang(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& g,
                std::vector<Stixel*>& group, const OverhangParams& p) {
  if (p.min_reach_m <= 0 || group.empty() || disparity.empty() || !g.valid || g.vd_slope <= 0) return -1;
  const int cw = std::max(1, p.column_width_px);
  const int cols = disparity.cols;
  const double fb = cam.fx * cam.baseline_m;
  int x0 = group.front()->u, x1 = x0, y0 = group.front()->top_row, y1 = group.front()->bottom_row;
  float dmin = group.front()->disparity, dmax = dmin;
  std::vector<float> disp;
  for (const Stixel* s : group) {
    x0 = std::min(x0, s->u), x1 = std::max(x1, s->u + s->width);
    y0 = std::min(y0, s->top_row), y1 = std::max(y1, s->bottom_row);
    dmin = std::min(dmin, s->disparity), dmax = std::max(dmax, s->disparity);
    disp.push_back(s->disparity);
  }
  std::nth_element(disp.begin(), disp.begin() + disp.size() / 2, disp.end());
  const float d = disp[disp.size() / 2];
  if (!(d > 0)) return -1;
  const float lo = dmin - disparityTolerance(dmin, cam, p.depth_tolerance_m);
  const float hi = dmax + disparityTolerance(dmax, cam, p.depth_tolerance_m);
  // Lowest row that may be cut: min_height_m over the road at the group's disparity.
  const float h = g.height_m;
  const float row_min = (d * (1.0f - p.min_height_m / h) - g.vd_intercept) / g.vd_slope;
  const int v_start = std::min(y1, static_cast<int>(std::floor(row_min)));
  if (v_start <= y0) return -1;
  const double z = fb / d;
  if (z > p.max_distance_m) return -1;
  const double width_m = (x1 - x0) * z / cam.fx;
  if (width_m < p.min_width_m || width_m > p.max_width_m) return -1;
  const int strips = std::max(1, static_cast<int>(std::ceil(p.min_reach_m * cam.fx / (z * cw))));
  const int need = std::max(1, static_cast<int>(std::ceil(p.min_fill * strips)));
  const int need_px = std::max(1, (2 * cw + 4) / 5);  // 40 % of a strip's pixels

  // Does the strip starting at column u0 hold pixels at the group's depth on row v?
  auto filled = [&](const float* row, float dg_road, int u0) {
    int n = 0;
    for (int u = std::max(0, u0); u < std::min(cols, u0 + cw); ++u)
      if (row[u] >= lo && row[u] <= hi && row[u] > dg_road) ++n;
    return n >= need_px;
  };
  auto side = [&](const float* row, float dg_road, int first_u, int step) {
    int hit = 0, miss = 0;
    for (int k = 0; k < strips; ++k) {
      const int u0 = first_u + step * k * cw;
      if (u0 + cw <= 0 || u0 >= cols) return false;  // the image ends: no evidence of a reach
      if (filled(row, dg_road, u0)) {
        if (++hit >= need) return true;
      } else if (++miss > strips - need) {
        return false;
      }
    }
    return false;
  };
  // A run counts only above a row without overhang: something at the
  // group's depth beside it on every row down to min_height_m stands there.
  int run = 0;
  bool clear_below = false;
  for (int v = v_start; v >= y0; --v) {
    const float* row = disparity.ptr<float>(v);
    // Road at this row: height h*(x - dg)/x <= tol  <=>  x <= h*dg/(h - tol).
    const float road_max = h * g.groundDisparity(static_cast<float>(v)) / (h - p.ground_tolerance_m);
    const bool over = side(row, road_max, x0 - cw, -1) || side(row, road_max, x1, +1);
    if (!over) clear_below = true;
    run = over && clear_below ? run + 1 : 0;
    if (run >= p.min_rows) {
      const int keep = v + p.min_rows;  // first row below the overhang
      bool cut = false;
      for (Stixel* s : group)
        if (s->top_row < keep && s->bottom_row > keep) s->top_row = keep, cut = true;
      return cut ? keep : -1;
    }
  }
  return -1;
}

}  // namespace nerv::stixel
