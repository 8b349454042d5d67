#include "box_refinement.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"

namespace nerv::stixel {

namespace {


// Pixels of column u, rows [y0, y1], within [lo, hi] and above the road:
// their number and the longest run of consecutive ones.
struct ColumnFill {
  int count = 0, longest_run = 0;
};
ColumnFill columnFill(const cv::Mat& disp, const GroundModel& g, float road_tol_m, int u, int y0, int y1,
                      float lo, float hi) {
  ColumnFill f;
  int run = 0;
  for (int v = y0; v <= y1; ++v) {
    const float x = disp.ptr<float>(v)[u];
    if (x >= lo && x <= hi && heightAboveGround(g, static_cast<float>(v), x) > road_tol_m) {
      ++f.count;
      f.longest_run = std::max(f.longest_run, ++run);
    } else {
      run = 0;
    }
  }
  return f;
}

}  // namespace

float occludedEdgeTolerance(const Stixel& s, int u, const StereoCamera& cam, float depth_tolerance_m,
                            float band_px, float max_px) {
  if (band_px <= 0) return max_px;
  const double fb = cam.fx * cam.baseline_m;
  const float metric = static_cast<float>(s.disparity * s.disparity * depth_tolerance_m / fb);
  const double uc = s.u + 0.5 * s.width;
  const double side_drop = uc > cam.cx && u < uc ? s.disparity * (uc - u) / (uc - cam.cx) : 0.0;
  return std::min(max_px, std::max(band_px, metric) + static_cast<float>(side_drop));
}

void refineBox(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
               const std::vector<const Stixel*>& group, int column_width_px,
               const BoxRefinementParams& p, PixelBox& box, int edge_rows_above, int min_x, int max_x) {
  if (group.empty() || disparity.empty()) return;
  const int cols = disparity.cols, cw = std::max(1, column_width_px);

  // Left and right edges: scan the edge stixel's strip and the strip outside it.
  const bool narrow = p.narrow_max_width_m > 0 &&
                      (box.x1 - box.x0) * group.front()->depth_m / cam.fx <= p.narrow_max_width_m;
  const float min_fill = narrow ? std::max(p.min_column_fill, p.narrow_min_column_fill) : p.min_column_fill;
  // occluded: the left edge's tolerance below the stixel's disparity.
  auto edgeOk = [&](const Stixel& s, int u, bool occluded) {
    if (u < 0 || u >= cols) return false;
    const float tol = disparityTolerance(s.disparity, cam, p.depth_tolerance_m);
    const float below =
        occluded ? occludedEdgeTolerance(s, u, cam, p.depth_tolerance_m, p.occluded_edge_tolerance_px, tol) : tol;
    int last = s.bottom_row;
    if (edge_rows_above < s.bottom_row && 4 * (edge_rows_above - s.top_row) >= s.bottom_row - s.top_row + 1)
      last = edge_rows_above - 1;
    const int rows = last - s.top_row + 1;
    const ColumnFill f = columnFill(disparity, ground, p.ground_tolerance_m, u, s.top_row, last,
                                    s.disparity - below, s.disparity + tol);
    const float run_px = p.min_column_run_m > 0 ? p.min_column_run_m * static_cast<float>(cam.fy) / s.depth_m : 1e9f;
    return f.count >= min_fill * rows || f.longest_run >= run_px;
  };
  // How far an edge may move outside the group (the object continues outside).
  auto reach = [&](const Stixel& s) {
    return std::max(cw, static_cast<int>(p.max_extension_m * static_cast<float>(cam.fx) / s.depth_m));
  };
  const Stixel& left = *group.front();
  const Stixel& right = *group.back();
  int x0 = box.x0, x1 = box.x1;
  // Left edge: the first column of the edge strip that passes, then outwards
  // from the strip's edge; with the occlusion band's tolerance first, and the
  // usual one when that leaves the whole strip (a low foot stixel whose rows
  // are mostly road), which would otherwise keep the union's edge.
  auto scanLeft = [&](bool occluded) {
    int u = left.u;
    const int end = left.u + left.width;
    while (u < end && !edgeOk(left, u, occluded)) ++u;
    if (u >= end) return false;
    if (u == left.u)
      while (u > left.u - reach(left) && edgeOk(left, u - 1, occluded)) --u;
    x0 = u;
    return true;
  };
  if (!scanLeft(p.occluded_edge_tolerance_px > 0)) scanLeft(false);
  {
    int u = right.u + right.width - 1;
    while (u >= right.u && !edgeOk(right, u, false)) --u;
    if (u >= right.u) {
      if (u == right.u + right.width - 1)
        while (u < right.u + right.width - 1 + reach(right) && edgeOk(right, u + 1, false)) ++u;
      x1 = u + 1;
    }
  }
  x0 = std::max(x0, min_x);
  x1 = std::min(x1, max_x);
  if (x1 - x0 < 1) return;

  // Top: first row (from the union's top down) where pixels at the group's
  // depths fill min_row_fill of the width, confirmed by the next row.
  float dmin = group.front()->disparity, dmax = dmin;
  for (const Stixel* s : group) dmin = std::min(dmin, s->disparity), dmax = std::max(dmax, s->disparity);
  const float lo = dmin - disparityTolerance(dmin, cam, p.depth_tolerance_m);
  const float hi = dmax + disparityTolerance(dmax, cam, p.depth_tolerance_m);
  const float need = p.min_row_fill * (x1 - x0);
  auto rowOk = [&](int v) {
    const float* row = disparity.ptr<float>(v);
    int n = 0;
    for (int u = x0; u < x1; ++u)
      if (row[u] >= lo && row[u] <= hi && heightAboveGround(ground, static_cast<float>(v), row[u]) > p.ground_tolerance_m) ++n;
    return n >= need;
  };
  int y0 = box.y0;
  while (y0 < box.y1 - 1 && !(rowOk(y0) && rowOk(y0 + 1))) ++y0;
  if (y0 >= box.y1 - 1) y0 = box.y0;  // nothing fills the box: keep the union
  box.x0 = x0;
  box.x1 = x1;
  box.y0 = y0;
}

}  // namespace nerv::stixel
