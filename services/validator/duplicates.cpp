#include "duplicates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace nerv::validator {

float boxIou(const Box& a, const Box& b) {
  const int w = std::min(a.x + a.w, b.x + b.w) - std::max(a.x, b.x);
  const int h = std::min(a.y + a.h, b.y + b.h) - std::max(a.y, b.y);
  if (w <= 0 || h <= 0) return 0.0f;
  const float inter = static_cast<float>(w) * static_cast<float>(h);
  const float uni = static_cast<float>(a.w) * a.h + static_cast<float>(b.w) * b.h - inter;
  return uni > 0 ? inter / uni : 0.0f;
}

int removeDuplicates(const std::vector<Hypothesis>& hyps, const std::vector<int>& normals,
                     std::vector<Verdict>& verdicts, const DuplicateParams& p) {
  if (p.min_iou <= 0 || hyps.size() != verdicts.size() || hyps.size() != normals.size()) return 0;
  // Weaker first in the ordering: fewer normals, then the smaller box, then the later one.
  auto weaker = [&](size_t i, size_t j) {
    if (normals[i] != normals[j]) return normals[i] < normals[j];
    const long ai = static_cast<long>(hyps[i].box.w) * hyps[i].box.h, aj = static_cast<long>(hyps[j].box.w) * hyps[j].box.h;
    if (ai != aj) return ai < aj;
    return i > j;
  };
  int removed = 0;
  for (size_t i = 0; i < hyps.size(); ++i) {
    for (size_t j = 0; j < hyps.size() && verdicts[i].kept; ++j) {
      if (i == j || !verdicts[j].kept || !weaker(i, j)) continue;
      const Hypothesis& a = hyps[i];
      const Hypothesis& b = hyps[j];
      if (!(a.z_m > 0 && b.z_m > 0) || std::abs(a.z_m - b.z_m) > p.max_depth_ratio * std::min(a.z_m, b.z_m)) continue;
      if (std::abs(a.box.y - b.box.y) > p.max_row_offset_px ||
          std::abs((a.box.y + a.box.h) - (b.box.y + b.box.h)) > p.max_row_offset_px)
        continue;
      const float o = boxIou(a.box, b.box);
      if (!(o > p.min_iou)) continue;
      char buf[96];
      std::snprintf(buf, sizeof buf, "duplicate of hypothesis %d (IoU %.2f, same rows and depth)", b.id, o);
      verdicts[i].kept = false;
      verdicts[i].reason = buf;
      ++removed;
    }
  }
  return removed;
}

}  // namespace nerv::validator
