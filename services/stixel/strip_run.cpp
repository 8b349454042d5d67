#include "strip_run.hpp"

#include <algorithm>

#include "height_steps.hpp"

namespace nerv::stixel {

StripRun describeRun(const std::vector<const Stixel*>& s, size_t a, size_t b, const StereoCamera& cam,
                     const GroundModel* ground) {
  StripRun run;
  std::vector<float> h, d;
  for (size_t k = a; k < b; ++k) h.push_back(topHeightOverRoad(*s[k], cam, ground)), d.push_back(s[k]->disparity);
  const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
  run.spread_px = *hi - *lo;
  std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  run.median_h = h[h.size() / 2];
  run.median_d = d[d.size() / 2];
  run.width_m = (s[b - 1]->u + s[b - 1]->width - s[a]->u) * s[a]->depth_m / static_cast<float>(cam.fx);
  return run;
}

}  // namespace nerv::stixel
