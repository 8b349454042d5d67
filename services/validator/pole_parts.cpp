#include "pole_parts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nerv::validator {

int removePoleParts(const std::vector<Hypothesis>& hyps, const std::vector<int>& normals,
                    std::vector<Verdict>& verdicts, const PolePartParams& p, float pole_max_width_m) {
  if (!(p.min_height_m > 0) || hyps.size() != verdicts.size() || hyps.size() != normals.size()) return 0;
  auto poleLike = [&](const Hypothesis& h) {
    return h.height_m >= p.min_height_m && h.width_m > 0 && h.width_m < pole_max_width_m && h.z_m > 0;
  };
  // i is the part of j: shorter, or as tall with fewer normals (then the later one).
  auto partOf = [&](size_t i, size_t j) {
    if (hyps[i].height_m != hyps[j].height_m) return hyps[i].height_m < hyps[j].height_m;
    if (normals[i] != normals[j]) return normals[i] < normals[j];
    return i > j;
  };
  int removed = 0;
  for (size_t i = 0; i < hyps.size(); ++i) {
    if (!verdicts[i].kept || !poleLike(hyps[i])) continue;
    for (size_t j = 0; j < hyps.size(); ++j) {
      if (i == j || !verdicts[j].kept || !poleLike(hyps[j]) || !partOf(i, j)) continue;
      const Hypothesis& a = hyps[i];
      const Hypothesis& b = hyps[j];
      if (std::abs(a.z_m - b.z_m) > p.max_depth_ratio * std::min(a.z_m, b.z_m)) continue;
      const int shared = std::min(a.box.x + a.box.w, b.box.x + b.box.w) - std::max(a.box.x, b.box.x);
      const int narrower = std::min(a.box.w, b.box.w);
      if (narrower <= 0 || shared < p.min_overlap * narrower) continue;
      char buf[112];
      std::snprintf(buf, sizeof buf, "part of the pole of hypothesis %d (%.0f %% of its columns, %.1f m tall)",
                    b.id, 100.0 * shared / narrower, b.height_m);
      verdicts[i].kept = false;
      verdicts[i].reason = buf;
      ++removed;
      break;
    }
  }
  return removed;
}

}  // namespace nerv::validator
