#include "camera_height.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "super_snv.hpp"

namespace nerv::snv {

float sampleMedian(const std::vector<float>& values) {
  const size_t n = values.size();
  if (n == 0) return std::numeric_limits<float>::quiet_NaN();
  const size_t mid = n / 2;
  float lo, hi;
  sampleRange(values.data(), n, lo, hi);
  if (!(lo < hi)) return lo;  // all equal
  std::vector<float> part;
  size_t below = 0;  // values before `part` in the sorted order
  if (n >= 256 && std::isfinite(lo) && std::isfinite(hi)) {
    // Only the n/16 buckets' worth of values around the middle rank go to
    // nth_element: bucket index floor((x - lo) * nb / (hi - lo)) is monotone
    // in x, so the buckets holding ranks mid - 1 and mid hold the median.
    const uint32_t nb = static_cast<uint32_t>(n / 16);
    const double scale = nb / (static_cast<double>(hi) - lo), lo_d = lo;
    std::vector<uint32_t> key(n), count(nb, 0);
    for (size_t i = 0; i < n; ++i)
      key[i] = std::min(nb - 1, static_cast<uint32_t>((static_cast<double>(values[i]) - lo_d) * scale));
    for (size_t i = 0; i < n; ++i) ++count[key[i]];
    const size_t first_rank = n % 2 ? mid : mid - 1;  // lowest rank needed
    uint32_t b0 = 0;
    while (below + count[b0] <= first_rank) below += count[b0++];
    uint32_t b1 = b0;
    size_t upto = below + count[b0];
    while (upto <= mid) upto += count[++b1];
    part.reserve(upto - below);
    for (size_t i = 0; i < n; ++i)
      if (key[i] >= b0 && key[i] <= b1) part.push_back(values[i]);
  } else {
    part = values;
  }
  const auto m = part.begin() + static_cast<long>(mid - below);
  std::nth_element(part.begin(), m, part.end());
  if (n % 2 == 1) return *m;
  const float upper = *m;
  const float lower = *std::max_element(part.begin(), m);
  return 0.5f * (lower + upper);
}

float medianCameraHeight(const std::vector<cv::Vec3f>& points, const cv::Vec3f& normal) {
  std::vector<float> h(points.size());
  for (size_t i = 0; i < points.size(); ++i) h[i] = -normal.dot(points[i]);
  return sampleMedian(h);
}

}  // namespace nerv::snv
