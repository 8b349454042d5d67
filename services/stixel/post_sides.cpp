#include "post_sides.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"

namespace nerv::stixel {

namespace {

// Longest count of pixels of column u (rows [y0, y1]) within [lo, hi] and above
// the road, with no valid pixel outside [lo, hi] between them.
int bridgedRun(const cv::Mat& disp, const GroundModel& g, float road_tol_m, int u, int y0, int y1, float lo,
               float hi) {
  int best = 0, run = 0;
  for (int v = y0; v <= y1; ++v) {
    const float x = disp.ptr<float>(v)[u];
    if (!(x > 0.0f) || !std::isfinite(x)) continue;  // a hole: neither counts nor breaks
    if (x >= lo && x <= hi && heightAboveGround(g, static_cast<float>(v), x) > road_tol_m)
      best = std::max(best, ++run);
    else
      run = 0;
  }
  return best;
}

}  // namespace

bool widenPostSides(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                    const std::vector<const Stixel*>& group, const PostSidesParams& p, PixelBox& box) {
  if (p.max_width_m <= 0 || group.empty() || disparity.empty() || box.x1 <= box.x0) return false;
  std::vector<float> d;
  for (const Stixel* s : group) d.push_back(s->disparity);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  const float disp = d[d.size() / 2];
  if (!(disp > 0)) return false;
  const double fb = cam.fx * cam.baseline_m;
  const double z = fb / disp;
  const double px_per_m = cam.fx / z;
  if ((box.x1 - box.x0) / px_per_m > p.max_width_m) return false;
  if ((box.y1 - box.y0 + 1) * z / cam.fy < p.min_height_m) return false;

  const float tol = disparityTolerance(disp, cam, p.depth_tolerance_m);
  const int run_px = std::max(1, static_cast<int>(std::lround(p.min_run_m * cam.fy / z)));
  const int reach = static_cast<int>(p.max_extension_m * px_per_m);
  const int max_gap = static_cast<int>(p.max_gap_m * px_per_m);
  auto ok = [&](int u) {
    return u >= 0 && u < disparity.cols &&
           bridgedRun(disparity, ground, p.ground_tolerance_m, u, box.y0, box.y1, disp - tol, disp + tol) >= run_px;
  };
  bool moved = false;
  for (int side = -1; side <= 1; side += 2) {
    const int edge = side < 0 ? box.x0 : box.x1 - 1;  // outermost column kept so far
    int best = edge, gap = 0;
    for (int k = 1; k <= reach && gap <= max_gap; ++k) {
      const int u = edge + side * k;
      if (ok(u)) best = u, gap = 0;
      else ++gap;
    }
    if (best == edge) continue;
    moved = true;
    if (side < 0) box.x0 = best;
    else box.x1 = best + 1;
  }
  return moved;
}

}  // namespace nerv::stixel
