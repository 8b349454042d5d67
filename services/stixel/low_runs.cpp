#include "low_runs.hpp"

#include <algorithm>

#include "stixel_height.hpp"

namespace nerv::stixel {

bool isLowRun(const std::vector<const Stixel*>& group, const StereoCamera& cam, const LowRunParams& p) {
  if (p.max_height_m <= 0.0f || group.empty() || static_cast<int>(group.size()) < std::max(1, p.min_stixels))
    return false;
  float near = group.front()->depth_m, far = near;
  std::vector<float> heights;
  heights.reserve(group.size());
  for (const Stixel* s : group) {
    near = std::min(near, s->depth_m);
    far = std::max(far, s->depth_m);
    heights.push_back(stixelHeightM(*s, cam));
  }
  if (far - near < p.min_depth_span_m) return false;
  const size_t q = std::min(heights.size() - 1, heights.size() * 9 / 10);
  std::nth_element(heights.begin(), heights.begin() + static_cast<long>(q), heights.end());
  return heights[q] < p.max_height_m;
}

}  // namespace nerv::stixel
