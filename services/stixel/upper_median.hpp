// The upper median of a set of values (the element at size / 2 once sorted),
// taken on a copy: the stixel rules' "median stixel" (its depth, its top over
// the road, a box edge over rows).
#pragma once

#include <algorithm>
#include <vector>

namespace nerv::stixel {

template <class T>
T upperMedian(std::vector<T> v) {
  if (v.empty()) return T{};
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace nerv::stixel
