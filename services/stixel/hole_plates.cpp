#include "hole_plates.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"
#include "group_disparity.hpp"
#include "upper_median.hpp"

namespace nerv::stixel {

int raiseToHolePlate(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& g,
                     const std::vector<const Stixel*>& group, const HolePlateParams& p, PixelBox& box) {
  if (p.max_width_m <= 0.0f || group.empty() || !g.valid) return 0;
  const float d = medianDisparity(group);
  if (!(d > 0.0f)) return 0;
  const double z = cam.depthFromDisparity(d);
  const int w = box.x1 - box.x0;
  if (w <= 0 || w * z / cam.fx > p.max_width_m) return 0;
  if (heightAboveGround(g, static_cast<float>(box.y0), d) < p.min_top_m) return 0;
  const float tol = disparityTolerance(d, cam, p.depth_tolerance_m);
  const int max_rows = static_cast<int>(std::floor(p.max_plate_height_m * cam.fy / z));
  const int min_rows = std::max(1, static_cast<int>(std::ceil(p.min_plate_height_m * cam.fy / z)));
  const int max_cols = static_cast<int>(std::floor(p.max_plate_width_m * cam.fx / z));
  auto hole = [&](float x) { return !(x > 0.0f) || !std::isfinite(x) || std::abs(x - d) <= tol; };

  // Walk up from the box's top while its columns are a hole (one row bridged).
  int top = box.y0, miss = 0;
  std::vector<int> left, right;  // bounded rows' hole extents [l, r)
  int rows = 0;
  bool closed = false;
  for (int v = box.y0 - 1; v >= 0; --v) {
    const float* row = disparity.ptr<float>(v);
    int n = 0;
    for (int u = box.x0; u < box.x1; ++u) n += hole(row[u]) ? 1 : 0;
    if (n < p.min_hole_share * w) {
      if (++miss > 1) {
        closed = true;  // two rows of valid pixels at another depth above the hole
        break;
      }
      continue;
    }
    miss = 0;
    top = v, ++rows;
    if (box.y0 - top > max_rows) break;  // longer than a plate: sky or a wall, not closed
    int l = box.x0, r = box.x1;
    while (l > 0 && box.x1 - l < max_cols && hole(row[l - 1])) --l;
    while (r < disparity.cols && r - box.x0 < max_cols && hole(row[r])) ++r;
    const bool bounded = l > 0 && r < disparity.cols && !hole(row[l - 1]) && !hole(row[r]) && r - l <= max_cols;
    if (bounded) left.push_back(l), right.push_back(r);
    if (v == 0) closed = true;  // a near plate cut by the image's top
  }
  if (!closed || box.y0 - top < min_rows || box.y0 - top > max_rows) return 0;
  if (2 * static_cast<int>(left.size()) < rows) return 0;  // the hole's sides are not bounded in most rows
  const int rose = box.y0 - top;
  box.y0 = top;
  box.x0 = std::min(box.x0, upperMedian(left));
  box.x1 = std::max(box.x1, upperMedian(right));
  return rose;
}

}  // namespace nerv::stixel
