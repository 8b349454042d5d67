#include "lone_posts.hpp"

#include <cstdlib>

namespace nerv::stixel {

std::vector<Stixel> findLonePosts(const std::vector<Stixel>& first_layer, const StereoCamera& cam,
                                  const LonePostParams& p) {
  std::vector<Stixel> posts;
  if (p.min_height_m <= 0) return posts;
  const long n = static_cast<long>(first_layer.size());
  for (long i = 0; i < n; ++i) {
    const Stixel& s = first_layer[static_cast<size_t>(i)];
    if (s.depth_m > p.max_distance_m) continue;
    if ((s.bottom_row - s.top_row + 1) * s.depth_m / cam.fy < p.min_height_m) continue;
    const int reach = p.side_strips * s.width;
    // Neighbours on one side (step -1 or +1 through the u-sorted list): at least
    // one within reach, and all of them far behind.
    auto farSide = [&](long step) {
      int seen = 0;
      for (long j = i + step; j >= 0 && j < n; j += step) {
        const Stixel& o = first_layer[static_cast<size_t>(j)];
        if (o.u == s.u) continue;
        if (std::abs(o.u - s.u) > reach) break;
        if (o.depth_m - s.depth_m < p.min_gap_m || s.disparity - o.disparity < p.min_step_px) return false;
        ++seen;
      }
      return seen > 0;
    };
    if (farSide(-1) && farSide(+1)) posts.push_back(s);
  }
  return posts;
}

}  // namespace nerv::stixel
