// A group's representative disparity: its median stixel's (the upper median),
// robust to one wrong stixel. The box rules that judge pixels against "the
// object's depth" (blended_tops, hole_plates) read it.
#pragma once

#include <algorithm>
#include <vector>

#include "perception_types.hpp"

namespace nerv::stixel {

inline float medianDisparity(const std::vector<const Stixel*>& group) {
  if (group.empty()) return 0.0f;
  std::vector<float> ds;
  ds.reserve(group.size());
  for (const Stixel* s : group) ds.push_back(s->disparity);
  std::nth_element(ds.begin(), ds.begin() + ds.size() / 2, ds.end());
  return ds[ds.size() / 2];
}

}  // namespace nerv::stixel
