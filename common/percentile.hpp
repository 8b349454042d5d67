// Nearest-rank percentile of a sample (p in [0, 1]; 0 for an empty sample): the
// figure the run summary, the latency breakdown and nerv_eval_detections print, and the
// stereo_matcher's rig checks use (p 0.5: the upper median).
#pragma once

#include <algorithm>
#include <vector>

namespace nerv {

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

}  // namespace nerv
