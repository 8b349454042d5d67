// A group's representative disparity: its median stixel's (the upper median),
// robust to one wrong stixel. The box rules that judge pixels against "the
// object's depth" (blended_tops, hole_plates) read it.
#pragma once

#include <utility>
#include <vector>

#include "perception_types.hpp"
#include "upper_median.hpp"

namespace nerv::stixel {

inline float medianDisparity(const std::vector<const Stixel*>& group) {
  std::vector<float> ds;
  ds.reserve(group.size());
  for (const Stixel* s : group) ds.push_back(s->disparity);
  return upperMedian(std::move(ds));
}

}  // namespace nerv::stixel
