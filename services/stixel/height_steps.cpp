#include "height_steps.hpp"

#include <algorithm>

#include "nearest_per_strip.hpp"
#include "upper_median.hpp"

namespace nerv::stixel {

// From the road line's row at the stixel's disparity, not from its bottom
// row, which for a stixel seen above an occluder is the occluder's top.
float topHeightOverRoad(const Stixel& s, const StereoCamera& cam, const GroundModel* g) {
  double foot = s.bottom_row + 1;
  if (g && g->valid && g->vd_slope > 0) foot = std::max(foot, static_cast<double>((s.disparity - g->vd_intercept) / g->vd_slope));
  return static_cast<float>((foot - s.top_row) * s.depth_m / cam.fy);
}

int findHeightStep(const std::vector<const Stixel*>& group, const StereoCamera& cam,
                   const GroundModel* ground, const HeightStepParams& p) {
  if ((p.min_step_m <= 0 && p.min_depth_step_m <= 0) || group.size() < 2) return -1;
  // One stixel per strip: the nearest (an occluded one above it is another object).
  const std::vector<const Stixel*> s = nearestPerStrip(group);
  const size_t n = s.size();
  const size_t rest = static_cast<size_t>(std::max(1, p.min_rest_stixels));
  if (n < rest + 1) return -1;
  float near_m = s[0]->depth_m;
  for (const Stixel* x : s) near_m = std::min(near_m, x->depth_m);
  if (near_m > p.max_distance_m) return -1;
  // A group cut by the image's bottom edge (a parked car within ~6 m) has no
  // foot in view; its silhouette is the image border's, not its own.
  for (const Stixel* x : s)
    if (x->bottom_row >= cam.height - 2) return -1;
  std::vector<float> h(n);
  for (size_t k = 0; k < n; ++k) h[k] = topHeightOverRoad(*s[k], cam, ground);

  // Ends of k strips, on the left (from_left) or the right; the best step wins.
  float best = p.min_step_m, best_px = 0;
  int cut_u = -1, depth_cut_u = -1;
  for (int from_left = 0; from_left < 2; ++from_left) {
    for (size_t k = 1; k + rest <= n; ++k) {
      // End strips [a, b), rest [c, d); `next` is the rest's strip at the cut.
      const size_t a = from_left ? 0 : n - k, b = from_left ? k : n;
      const size_t c = from_left ? k : 0, d = from_left ? n : n - k;
      const size_t next = from_left ? k : n - k - 1;
      const float width_m = (s[b - 1]->u + s[b - 1]->width - s[a]->u) * s[a]->depth_m / static_cast<float>(cam.fx);
      if (width_m > p.max_width_m) break;
      const float rest_width_m =
          (s[d - 1]->u + s[d - 1]->width - s[c]->u) * s[c]->depth_m / static_cast<float>(cam.fx);
      if (rest_width_m < p.min_rest_width_m) continue;
      const float end_h = upperMedian(std::vector<float>(h.begin() + a, h.begin() + b));
      if (end_h > p.max_height_m) continue;
      const int cut = s[from_left ? k : n - k]->u;
      if (p.min_step_m > 0 && end_h >= p.min_height_m) {
        const float rest_h = std::max(h[next], upperMedian(std::vector<float>(h.begin() + c, h.begin() + d)));
        // Ties go to the narrower end (a strip more of the vehicle is not the road user).
        if (end_h - rest_h > best || (cut_u < 0 && end_h - rest_h >= best)) best = end_h - rest_h, cut_u = cut;
      }
      // Depth: a flat end whose two neighbours in the rest are both farther
      // by a clear disparity step (the grouping gap joined them).
      if (p.min_depth_step_m <= 0 || end_h < p.depth_step_min_height_m || d - c < 2) continue;
      float lo = s[a]->disparity, hi = lo;
      std::vector<float> ed;
      for (size_t j = a; j < b; ++j) lo = std::min(lo, s[j]->disparity), hi = std::max(hi, s[j]->disparity), ed.push_back(s[j]->disparity);
      if (hi - lo > p.max_end_spread_px) continue;
      const float end_d = upperMedian(ed);
      const size_t next2 = from_left ? k + 1 : n - k - 2;
      const float d1 = s[next]->disparity - end_d, d2 = s[next2]->disparity - end_d;
      // Only an end nearer than the rest: an end farther than its
      // neighbours is as often a vehicle's receding side (a van's) as a
      // road user behind it.
      const float step_px = std::min(-d1, -d2);
      const float step_m = static_cast<float>(cam.depthFromDisparity(end_d - step_px) - cam.depthFromDisparity(end_d));
      if (step_px >= p.min_depth_step_px && step_m >= p.min_depth_step_m && step_px > best_px)
        best_px = step_px, depth_cut_u = cut;
    }
  }
  return cut_u >= 0 ? cut_u : depth_cut_u;
}

}  // namespace nerv::stixel
