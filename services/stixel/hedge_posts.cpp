#include "hedge_posts.hpp"

#include <algorithm>

#include "stixel_height.hpp"

namespace nerv::stixel {

std::pair<size_t, size_t> findHedgePost(const std::vector<const Stixel*>& g, const StereoCamera& cam,
                                        const HedgePostParams& p) {
  const std::pair<size_t, size_t> none{0, 0};
  if (p.min_ratio <= 0 || g.size() < 2) return none;
  for (size_t k = 1; k < g.size(); ++k)
    if (g[k]->u == g[k - 1]->u) return none;  // two layers: not a silhouette along u
  for (const Stixel* s : g)
    if (s->bottom_row >= cam.height - 2) return none;  // cut by the image border: not its silhouette
  const size_t n = g.size();
  for (size_t k = 0; k < n;) {
    if (stixelHeightM(*g[k], cam) < p.min_height_m) {
      ++k;
      continue;
    }
    size_t e = k;
    float low = 1e9f;
    int top = g[k]->top_row;
    while (e < n && stixelHeightM(*g[e], cam) >= p.min_height_m) {
      low = std::min(low, stixelHeightM(*g[e], cam));
      top = std::min(top, g[e]->top_row);
      ++e;
    }
    const float width_m = (g[e - 1]->u + g[e - 1]->width - g[k]->u) * g[k]->depth_m / static_cast<float>(cam.fx);
    // Hedge on both sides, or at one end with the rest of the group on the
    // run's far side from cx. Any tall run at a group's end is as often a
    // car's rear beside its lower receding side (synthetic wet_road 7, wet_road
    // 5, urban 11: 8 false positives at 23-29 m); but the side of a car in view
    // is the one facing the optical axis, so that lower side always lies
    // between the rear and cx. KITTI 0926's median-hedge posts at a group's
    // end have the hedge on the outer side.
    const bool inside = k > 0 && e < n;
    const bool rest_outward = p.at_group_end && (k == 0) != (e == n) &&
                              (k == 0 ? g[0]->u >= cam.cx : g[n - 1]->u + g[n - 1]->width <= cam.cx);
    if ((inside || rest_outward) && width_m <= p.max_width_m && g[k]->depth_m <= p.max_distance_m) {
      bool ok = true;
      for (size_t j = 0; j < n && ok; ++j)
        if ((j < k || j >= e) && stixelHeightM(*g[j], cam) * p.min_ratio > low) ok = false;
      for (size_t j : {k - 1, e}) {
        if (j >= n) continue;  // k - 1 wrapped (run at the left end) or e == n: no neighbour there
        const Stixel& nb = *g[j];
        const float step_m = static_cast<float>((nb.top_row - top) * nb.depth_m / cam.fy);
        if (stixelHeightM(nb, cam) * p.min_ratio > low || step_m < p.min_step_m) ok = false;
      }
      if (ok) return {k, e};
    }
    k = e;
  }
  return none;
}

}  // namespace nerv::stixel
