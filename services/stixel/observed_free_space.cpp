#include "observed_free_space.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::stixel {

ObservedFreeSpace observeFreeSpace(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& g,
                                   const std::vector<int>& boundary, const ObservedParams& p) {
  ObservedFreeSpace out;
  out.column_width_px = p.column_width_px;
  out.min_observed = p.min_observed;
  const int strips = p.column_width_px > 0 ? (disparity.cols + p.column_width_px - 1) / p.column_width_px : 0;
  out.observed.assign(strips, 0.0f);
  const bool usable = g.valid && g.vd_slope > 0 && static_cast<int>(boundary.size()) == strips;
  if (!usable) {
    out.num_unobserved = strips;
    return out;
  }
  const float far_d = static_cast<float>(cam.disparityFromDepth(p.max_distance_m));
  int64_t measured_all = 0, pixels_all = 0;
  for (int s = 0; s < strips; ++s) {
    const int u0 = s * p.column_width_px, u1 = std::min(disparity.cols, u0 + p.column_width_px);
    const float d_end = boundary[s] >= 0 ? static_cast<float>(boundary[s]) : far_d;
    // The road reaches d_end at this row; the strip's free space lies below it.
    const double v_end = std::ceil((d_end - g.vd_intercept) / g.vd_slope);
    const int v0 = static_cast<int>(std::clamp(v_end, 0.0, static_cast<double>(disparity.rows)));
    int64_t measured = 0;
    for (int v = v0; v < disparity.rows; ++v) {
      const float* row = disparity.ptr<float>(v);
      for (int u = u0; u < u1; ++u) measured += (row[u] > 0.0f && std::isfinite(row[u])) ? 1 : 0;
    }
    const int64_t pixels = static_cast<int64_t>(disparity.rows - v0) * (u1 - u0);
    // An obstacle at the image's lower edge leaves no free space: nothing unseen.
    out.observed[s] = pixels > 0 ? static_cast<float>(measured) / pixels : 1.0f;
    if (out.observed[s] < p.min_observed) ++out.num_unobserved;
    measured_all += measured;
    pixels_all += pixels;
  }
  out.observed_share = pixels_all > 0 ? static_cast<float>(measured_all) / pixels_all : 1.0f;
  return out;
}

}  // namespace nerv::stixel
