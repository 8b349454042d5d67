#include "person_pairs.hpp"

#include <algorithm>
#include <cmath>

#include "nearest_per_strip.hpp"
#include "strip_run.hpp"

namespace nerv::stixel {

GapCut findPersonPair(const std::vector<const Stixel*>& group, const StereoCamera& cam, const GroundModel* ground,
                      const PersonPairParams& p) {
  GapCut none;
  if (p.min_step_px <= 0 || group.size() < 2) return none;
  const std::vector<const Stixel*> s = nearestPerStrip(group);
  const size_t n = s.size();
  if (n < 2) return none;
  for (const Stixel* x : s)
    if (x->bottom_row >= cam.height - 2) return none;  // cut by the image's bottom edge
  const float total_m = (s[n - 1]->u + s[n - 1]->width - s[0]->u) * s[0]->depth_m / static_cast<float>(cam.fx);
  if (total_m > 2 * p.max_width_m) return none;
  auto person = [&](const StripRun& x) {
    return x.width_m >= p.min_width_m && x.width_m <= p.max_width_m && x.median_h >= p.min_height_m &&
           x.median_h <= p.max_height_m && x.spread_px <= p.max_spread_px;
  };
  float best = 0;
  GapCut cut;
  // Left part [0, k), right part [k + blend, n); the blended strips between
  // them read between the two and belong to neither.
  for (int blend = 0; blend <= std::max(0, p.max_blend_strips); ++blend) {
    for (size_t k = 1; k + static_cast<size_t>(blend) < n; ++k) {
      const size_t r0 = k + static_cast<size_t>(blend);
      if (blend > 0 && std::min(k, n - r0) < static_cast<size_t>(std::max(1, p.min_blend_part_strips))) continue;
      const StripRun l = describeRun(s, 0, k, cam, ground), r = describeRun(s, r0, n, cam, ground);
      if (!person(l) || !person(r)) continue;
      const float lo_d = std::min(l.median_d, r.median_d), hi_d = std::max(l.median_d, r.median_d);
      bool between = true;
      for (size_t q = k; q < r0; ++q) between = between && s[q]->disparity > lo_d && s[q]->disparity < hi_d;
      if (!between) continue;
      const float step_px = hi_d - lo_d;
      const float step_m = static_cast<float>(std::abs(cam.depthFromDisparity(l.median_d) - cam.depthFromDisparity(r.median_d)));
      if (step_px >= p.min_step_px && step_m >= p.min_step_m && step_px > best)
        best = step_px, cut.found = true, cut.lo = s[k]->u, cut.hi = s[r0]->u;
    }
  }
  return cut;
}

}  // namespace nerv::stixel
