#include "layered_tops.hpp"

#include <algorithm>
#include <cmath>

#include "ground_geometry.hpp"
#include "stixel_extraction.hpp"

namespace nerv::stixel {

int lowerLayeredTops(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                     std::vector<Stixel*>& group, const LayerTopParams& p) {
  if (p.min_separation_m <= 0 || group.empty() || !ground.valid || disparity.empty()) return 0;
  std::vector<float> d, tops;
  int x0 = disparity.cols, x1 = 0, min_top = disparity.rows;
  for (const Stixel* s : group) {
    d.push_back(s->disparity);
    tops.push_back(static_cast<float>(s->top_row));
    x0 = std::min(x0, s->u);
    x1 = std::max(x1, s->u + s->width);
    min_top = std::min(min_top, s->top_row);
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  std::nth_element(tops.begin(), tops.begin() + tops.size() / 2, tops.end());
  const float d1 = d[d.size() / 2];
  const int median_top = static_cast<int>(tops[tops.size() / 2]);
  if (d1 <= 0 || median_top - min_top < p.min_rows) return 0;
  const double fb = cam.fx * cam.baseline_m;
  const double z1 = fb / d1;
  if ((x1 - x0) * z1 / cam.fx < p.min_width_m) return 0;
  x0 = std::max(0, x0), x1 = std::min(disparity.cols, x1);

  // The layer: the median of the pixels above the median top that are neither
  // background to the segmentation nor nearer than the group by as much.
  std::vector<float> up;
  for (int v = std::max(0, min_top); v < median_top; ++v) {
    const float* row = disparity.ptr<float>(v);
    for (int u = x0; u < x1; ++u) {
      const float x = row[u];
      if (!(x > 0 && std::isfinite(x)) || std::abs(x - d1) > p.max_separation_px) continue;
      if (heightAboveGround(ground, static_cast<float>(v), x) <= p.ground_tolerance_m) continue;
      up.push_back(x);
    }
  }
  if (up.size() < static_cast<size_t>(p.min_rows)) return 0;
  std::nth_element(up.begin(), up.begin() + up.size() / 2, up.end());
  const float d2 = up[up.size() / 2];
  const float min_sep = std::max(p.min_separation_px, static_cast<float>(d1 - fb / (z1 + p.min_separation_m)));
  if (d1 - d2 < min_sep) return 0;
  const float mid = 0.5f * (d1 + d2);
  const auto behind = std::count_if(up.begin(), up.end(), [&](float x) { return x < mid; });
  if (behind < p.min_layer_share * static_cast<float>(up.size())) return 0;

  int lowered = 0;
  for (Stixel* s : group) {
    if (s->top_row >= median_top || s->disparity <= mid) continue;
    TopSearch t;
    t.tolerance_px = s->disparity - mid;
    const int top = segmentTopRow(disparity, ground, p.ground_tolerance_m, s->u, std::min(disparity.cols, s->u + s->width),
                                  s->bottom_row, s->top_row, s->disparity, t);
    if (top > s->top_row) s->top_row = top, ++lowered;
  }
  return lowered;
}

}  // namespace nerv::stixel
