#include "stixel_reference.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::stixel {

std::vector<Stixel> referenceStixels(const cv::Mat& disparity, const StereoCamera& cam,
                                     const GroundModel& g, const Params& p) {
  std::vector<Stixel> out;
  const double th = g.pitch_deg * M_PI / 180.0;
  const double cos_th = std::cos(th), sin_th = std::sin(th);  // once, as any plain version would
  auto heightOverRoad = [&](int u, int v, float d) {
    const Point3 q = cam.toPoint(u, v, d);
    return g.height_m - (q.y * cos_th + q.z * sin_th);
  };
  auto valid = [&](float d) { return std::isfinite(d) && d > 0 && d < p.max_disparity_px; };
  const int cw = p.column_width_px;
  for (int u0 = 0; u0 < disparity.cols; u0 += cw) {
    const int u1 = std::min(disparity.cols, u0 + cw);
    std::vector<float> obstacle;  // disparities of the strip's obstacle pixels
    for (int v = 0; v < disparity.rows; ++v)
      for (int u = u0; u < u1; ++u) {
        const float d = disparity.at<float>(v, u);
        if (!valid(d) || cam.depthFromDisparity(d) > p.max_distance_m) continue;
        const double hg = heightOverRoad(u, v, d);
        if (hg > p.ground_tolerance_m && hg < p.max_height_above_ground_m) obstacle.push_back(d);
      }
    if (obstacle.empty()) continue;
    const int dmax = static_cast<int>(*std::max_element(obstacle.begin(), obstacle.end()));
    for (int k = dmax; k >= 1; --k) {
      std::vector<float> near_k;
      for (float d : obstacle)
        if (d >= k - 1 && d < k + 2) near_k.push_back(d);
      // count/width rows, each Z/fy metres tall.
      const double filled = near_k.size() / double(u1 - u0) * cam.depthFromDisparity(k + 0.5) / cam.fy;
      if (filled < p.min_obstacle_height_m) continue;
      std::sort(near_k.begin(), near_k.end());
      const float d = near_k[near_k.size() / 2];
      const int foot = std::clamp(static_cast<int>(std::lround((d - g.vd_intercept) / g.vd_slope)), 0,
                                  disparity.rows - 1);
      int top = foot, gap = 0;
      for (int v = foot; v >= 0 && gap <= 3; --v) {
        bool hit = false;
        for (int u = u0; u < u1; ++u) {
          const float x = disparity.at<float>(v, u);
          hit = hit || (valid(x) && std::abs(x - d) <= 1.0f);
        }
        if (hit) top = v, gap = 0;
        else ++gap;
      }
      Stixel s;
      s.u = u0;
      s.width = u1 - u0;
      s.top_row = top;
      s.bottom_row = foot;
      s.disparity = d;
      s.depth_m = static_cast<float>(cam.depthFromDisparity(d));
      const Point3 base = cam.toPoint(0.5 * (u0 + u1), foot, d);
      s.base_x_m = static_cast<float>(base.x);
      s.base_y_m = static_cast<float>(base.y);
      s.base_z_m = static_cast<float>(base.z);
      out.push_back(s);
      break;
    }
  }
  return out;
}

}  // namespace nerv::stixel
