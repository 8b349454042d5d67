#include "hypothesis_grouping.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::stixel {

namespace {

// Depth and lateral gap between a stixel and the group's last member.
bool joins(const std::vector<const Stixel*>& group, const Stixel& s, const StereoCamera& cam,
           const GroupingParams& p) {
  const Stixel& g = *group.back();
  const float dz = std::abs(g.depth_m - s.depth_m);
  const float z = std::min(g.depth_m, s.depth_m);
  const float gap_px = static_cast<float>(s.u - (g.u + g.width));
  const float lateral_m = std::max(0.0f, gap_px) * z / static_cast<float>(cam.fx);
  return dz <= p.group_depth_gap_m && lateral_m <= p.group_lateral_gap_m;
}

}  // namespace

std::vector<Hypothesis> groupStixels(const std::vector<Stixel>& stixels, const StereoCamera& cam,
                                     const GroupingParams& p, const GroupingInput& input) {
  std::vector<std::vector<const Stixel*>> groups;
  for (const Stixel& s : stixels) {
    const size_t n = groups.size();
    if (n > 0 && joins(groups[n - 1], s, cam, p)) {
      groups[n - 1].push_back(&s);
    } else if (n > 1 && groups[n - 1].size() == 1 && joins(groups[n - 2], s, cam, p)) {
      // One stray stixel (a window, a reflection, a thin post in front) does not
      // cut an object in two: the object continues behind it.
      groups[n - 2].push_back(&s);
      std::swap(groups[n - 2], groups[n - 1]);
    } else {
      groups.push_back({&s});
    }
  }

  std::vector<Hypothesis> out;
  std::vector<float> disp;
  for (const auto& g : groups) {
    if (static_cast<int>(g.size()) < std::max(1, p.min_stixels_per_hypothesis)) {
      // A lone tall stixel is a post or a sign, not noise.
      const Stixel& s = *g.front();
      const bool tall_single = g.size() == 1 && p.min_single_stixel_height_m > 0 &&
                               (s.bottom_row - s.top_row + 1) * s.depth_m / cam.fy >= p.min_single_stixel_height_m;
      if (!tall_single) continue;
    }
    int x0 = g.front()->u, x1 = g.front()->u + g.front()->width;
    int y0 = g.front()->top_row, y1 = g.front()->bottom_row;
    disp.clear();
    for (const Stixel* s : g) {
      x0 = std::min(x0, s->u);
      x1 = std::max(x1, s->u + s->width);
      y0 = std::min(y0, s->top_row);
      y1 = std::max(y1, s->bottom_row);
      disp.push_back(s->disparity);
    }
    if (p.refine_boxes && input.disparity && input.ground) {
      PixelBox box{x0, x1, y0, y1};
      refineBox(*input.disparity, cam, *input.ground, g, p.column_width_px, p.refinement, box);
      x0 = box.x0, x1 = box.x1, y0 = box.y0;
    }
    // Representative disparity: the median stixel (robust to one wrong stixel).
    std::nth_element(disp.begin(), disp.begin() + disp.size() / 2, disp.end());
    const float d = disp[disp.size() / 2];
    const double z = cam.depthFromDisparity(d);
    // Base centre: the box's middle column on the ground below the median stixel.
    double foot_v = 0;
    for (const Stixel* s : g)
      if (s->disparity == d) foot_v = s->bottom_row;
    const Point3 base = cam.toPoint(0.5 * (x0 + x1), foot_v, d);

    Hypothesis hy;
    hy.box = {x0, y0, x1 - x0, y1 - y0 + 1};
    hy.x_m = static_cast<float>(base.x);
    hy.y_m = static_cast<float>(base.y);
    hy.z_m = static_cast<float>(base.z);
    hy.width_m = static_cast<float>((x1 - x0) * z / cam.fx);
    hy.height_m = static_cast<float>((y1 - y0 + 1) * z / cam.fy);
    hy.distance_m =
        static_cast<float>(std::sqrt(base.x * base.x + base.y * base.y + base.z * base.z));
    hy.disparity = d;
    hy.num_stixels = static_cast<int>(g.size());
    if (hy.height_m < p.min_obstacle_height_m || hy.distance_m > p.max_distance_m) continue;
    out.push_back(hy);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.box.x < b.box.x; });
  for (size_t i = 0; i < out.size(); ++i) out[i].id = static_cast<int>(i);
  return out;
}

}  // namespace nerv::stixel
