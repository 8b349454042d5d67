#include "obstacle_map.hpp"

#include <algorithm>
#include <limits>

#include "ground_geometry.hpp"

namespace nerv::stixel {

cv::Mat obstacleDisparityMap(const cv::Mat& disparity, const GroundModel& g, const FreeSpaceParams& fs) {
  CV_Assert(disparity.type() == CV_32F);
  cv::Mat out(disparity.size(), CV_32F);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float tol = fs.ground_tolerance_m, top = fs.max_height_above_ground_m;
  for (int v = 0; v < disparity.rows; ++v) {
    const float* d = disparity.ptr<float>(v);
    float* o = out.ptr<float>(v);
    const float fv = static_cast<float>(v);
    for (int u = 0; u < disparity.cols; ++u) {
      const float hg = heightAboveGround(g, fv, d[u]);
      o[u] = hg > tol && hg < top ? d[u] : nan;
    }
  }
  return out;
}

float medianInRange(const cv::Mat& obstacle_map, int u0, int u1, int v0, int v1, float lo, float hi,
                    std::vector<float>& samples) {
  samples.clear();
  for (int v = v0; v <= v1; ++v) {
    const float* row = obstacle_map.ptr<float>(v);
    for (int u = u0; u < u1; ++u)
      if (row[u] >= lo && row[u] < hi) samples.push_back(row[u]);  // NaN fails
  }
  if (samples.empty()) return 0.0f;
  auto mid = samples.begin() + samples.size() / 2;
  std::nth_element(samples.begin(), mid, samples.end());
  return *mid;
}

}  // namespace nerv::stixel
