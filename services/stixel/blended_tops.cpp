#include "blended_tops.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"
#include "group_disparity.hpp"

namespace nerv::stixel {

int raiseBlendedTop(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& g,
                    const std::vector<const Stixel*>& group, const BlendedTopParams& p, PixelBox& box) {
  if (p.max_extension_m <= 0.0f || group.empty() || !g.valid) return 0;
  const float d = medianDisparity(group);
  if (!(d > 0.0f)) return 0;
  const double z = cam.depthFromDisparity(d);
  const int w = box.x1 - box.x0;
  if (z < p.min_distance_m || w <= 0 || w * z / cam.fx > p.max_width_m) return 0;
  const float top_m = heightAboveGround(g, static_cast<float>(box.y0), d);
  if (top_m < p.min_top_m || top_m > p.max_top_m) return 0;
  const int reach = static_cast<int>(std::floor(p.max_extension_m * cam.fy / z));
  const int v_top = std::max(0, box.y0 - reach);
  if (v_top >= box.y0) return 0;
  const float tol = disparityTolerance(d, cam, p.depth_tolerance_m);

  // Background: the median of the farther pixels beside the box, one box width
  // on either side, over the rows searched.
  std::vector<float> bg;
  for (int v = v_top; v < box.y0; ++v) {
    const float* row = disparity.ptr<float>(v);
    for (int u = std::max(0, box.x0 - w); u < std::min(disparity.cols, box.x1 + w); ++u) {
      if (u >= box.x0 && u < box.x1) continue;
      const float x = row[u];
      if (x > 0.0f && std::isfinite(x) && x < d - tol) bg.push_back(x);
    }
  }
  float back = 0.0f;  // nothing matched beside the box: the sky
  if (!bg.empty()) {
    std::nth_element(bg.begin(), bg.begin() + bg.size() / 2, bg.end());
    back = bg[bg.size() / 2];
  }
  const float blend_lo = back + p.min_share * (d - back);

  // Walk up while the rows keep a blend (one row without any bridged); a row
  // mostly nearer than the body is an occluder above it and ends the walk.
  int top = box.y0, empty_run = 0;
  for (int v = box.y0 - 1; v >= v_top; --v) {
    const float* row = disparity.ptr<float>(v);
    int blend = 0, nearer = 0, valid = 0;
    for (int u = box.x0; u < box.x1; ++u) {
      const float x = row[u];
      if (!(x > 0.0f) || !std::isfinite(x)) continue;
      ++valid;
      if (x > d + tol) ++nearer;
      else if (x >= blend_lo) ++blend;
    }
    if (2 * nearer > valid && valid > 0) break;
    if (blend >= 2) {
      top = v, empty_run = 0;
    } else if (++empty_run > 1) {
      break;
    }
  }
  const int rose = box.y0 - top;
  box.y0 = top;
  return rose;
}

}  // namespace nerv::stixel
