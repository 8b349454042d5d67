#include "occluded_vehicles.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::stixel {

void widenOccludedVehicles(std::vector<Hypothesis>& hs, const StereoCamera& cam, const OccludedVehicleParams& p) {
  if (p.vehicle_width_m <= 0.0f) return;
  const std::vector<Hypothesis> before = hs;  // occluders are judged by their boxes before any widening
  for (size_t i = 0; i < hs.size(); ++i) {
    Hypothesis& a = hs[i];
    if (a.width_m < p.min_width_m || a.width_m >= p.max_width_m || a.height_m < p.min_height_m ||
        a.height_m > p.max_height_m || !(a.z_m > 0.0f))
      continue;
    const int ax0 = a.box.x, ax1 = a.box.x + a.box.w, ay0 = a.box.y, ay1 = a.box.y + a.box.h;
    int left_edge = -1, right_edge = -1;  // the occluders' far edges, per side
    for (size_t j = 0; j < before.size(); ++j) {
      const Hypothesis& b = before[j];
      if (j == i || !(b.z_m > 0.0f) || b.z_m > a.z_m - p.min_depth_step_m) continue;
      const int bx0 = b.box.x, bx1 = b.box.x + b.box.w, by0 = b.box.y, by1 = b.box.y + b.box.h;
      if (by1 < ay1 - 3 || by0 > ay0 + a.box.h / 2) continue;  // it must cover the bottom and half the height
      if (bx0 <= ax1 + p.touch_px && bx0 >= ax0 + a.box.w / 2 && bx1 > ax1) right_edge = std::max(right_edge, bx1);
      if (bx1 >= ax0 - p.touch_px && bx1 <= ax1 - a.box.w / 2 && bx0 < ax0)
        left_edge = left_edge < 0 ? bx0 : std::min(left_edge, bx0);
    }
    if ((left_edge >= 0) == (right_edge >= 0)) continue;  // no occluder, or one on each side
    const int want = static_cast<int>(std::lround(p.vehicle_width_m * cam.fx / a.z_m));
    if (want <= a.box.w) continue;
    if (right_edge >= 0) {
      a.box.w = std::min(ax0 + want, right_edge) - ax0;
    } else {
      const int x0 = std::max(ax1 - want, left_edge);
      a.box.w = ax1 - x0, a.box.x = x0;
    }
    a.width_m = static_cast<float>(a.box.w * a.z_m / cam.fx);
    a.x_m = static_cast<float>((a.box.x + 0.5 * a.box.w - cam.cx) * a.z_m / cam.fx);
  }
}

}  // namespace nerv::stixel
