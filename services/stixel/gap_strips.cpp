#include "gap_strips.hpp"

#include <algorithm>

#include "height_steps.hpp"
#include "nearest_per_strip.hpp"

namespace nerv::stixel {

GapCut findGapStrips(const std::vector<const Stixel*>& group, const StereoCamera& cam, const GroundModel* ground,
                     const GapStripParams& p) {
  GapCut none;
  if (p.min_dip_px <= 0 || group.size() < 2) return none;
  const std::vector<const Stixel*> s = nearestPerStrip(group);
  const int n = static_cast<int>(s.size());
  const float fx = static_cast<float>(cam.fx);
  // Disparity x is a gap's against a side's ref: farther by min_dip_px and min_dip_m.
  auto farther = [&](float x, float ref) {
    return x <= ref - p.min_dip_px && (x <= 0 || cam.depthFromDisparity(x) - cam.depthFromDisparity(ref) >= p.min_dip_m);
  };
  // End strips [a, b) at the left (from_left) or right end; gap strips next to them.
  for (int from_left = 1; from_left >= 0; --from_left) {
    for (int k = std::max(1, p.min_end_stixels); k < n; ++k) {
      const int a = from_left ? 0 : n - k, b = from_left ? k : n;
      const float width_m = (s[b - 1]->u + s[b - 1]->width - s[a]->u) * s[a]->depth_m / fx;
      if (width_m > p.max_end_width_m) break;
      float lo = s[a]->disparity, hi = lo;
      std::vector<float> h;
      for (int j = a; j < b; ++j) {
        lo = std::min(lo, s[j]->disparity), hi = std::max(hi, s[j]->disparity);
        h.push_back(topHeightOverRoad(*s[j], cam, ground));
      }
      if (hi - lo > p.max_spread_px) continue;
      std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
      const float end_h = h[h.size() / 2];
      if (end_h < p.min_height_m || end_h > p.max_height_m) continue;
      // Gap strips: consecutive strips beyond the end, each farther than the
      // end's farthest stixel by min_dip_px, spanning at most max_gap_m.
      const int step = from_left ? 1 : -1;
      int j = from_left ? b : a - 1;
      float gap_d = 1e9f;
      int count = 0;
      while (j >= 0 && j < n && farther(s[j]->disparity, lo)) {
        const int first = from_left ? b : j, last = from_left ? j : a - 1;
        const float span_m = (s[last]->u + s[last]->width - s[first]->u) * s[j]->depth_m / fx;
        if (span_m > p.max_gap_m) break;
        gap_d = std::min(gap_d, s[j]->disparity);
        ++count;
        j += step;
      }
      if (count == 0) continue;
      const bool ends = j < 0 || j >= n;
      // Hit the span limit with more farther strips beyond: a ramp, not a gap.
      if (!ends && farther(s[j]->disparity, lo)) continue;
      if (!ends && !farther(gap_d, s[j]->disparity)) continue;
      GapCut c;
      c.found = true;
      if (from_left) {
        c.lo = s[b]->u;
        c.hi = ends ? s[n - 1]->u + s[n - 1]->width : s[j]->u;
      } else {
        c.lo = ends ? s[0]->u : s[j]->u + s[j]->width;
        c.hi = s[a]->u;
      }
      return c;
    }
  }
  return none;
}

}  // namespace nerv::stixel
