#include "camera_height.hpp"

#include <algorithm>
#include <limits>

namespace nerv::snv {

float medianCameraHeight(const std::vector<cv::Vec3f>& points, const cv::Vec3f& normal) {
  if (points.empty()) return std::numeric_limits<float>::quiet_NaN();
  std::vector<float> h;
  h.reserve(points.size());
  for (const cv::Vec3f& p : points) h.push_back(-normal.dot(p));
  const auto mid = h.begin() + static_cast<long>(h.size() / 2);
  std::nth_element(h.begin(), mid, h.end());
  if (h.size() % 2 == 1) return *mid;
  const float upper = *mid;
  const float lower = *std::max_element(h.begin(), mid);
  return 0.5f * (lower + upper);
}

}  // namespace nerv::snv
