#include "super_snv.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nerv::snv {

cv::Vec3f normalFromPitchRoll(float pitch_deg, float roll_deg) {
  const double tp = std::tan(pitch_deg * CV_PI / 180.0), tr = std::tan(roll_deg * CV_PI / 180.0);
  const double len = std::sqrt(tp * tp + tr * tr + 1.0);
  return cv::Vec3f(static_cast<float>(-tr / len), static_cast<float>(-1.0 / len),
                   static_cast<float>(-tp / len));
}

float AngleHistogram::modeDeg() const {
  if (counts.empty()) return std::numeric_limits<float>::quiet_NaN();
  const auto best = std::max_element(counts.begin(), counts.end()) - counts.begin();
  if (counts[best] == 0) return std::numeric_limits<float>::quiet_NaN();
  return origin_deg + (static_cast<float>(best) + 0.5f) * bin_deg;
}

AngleHistogram buildAngleHistogram(const std::vector<float>& values_deg, float bin_deg) {
  CV_Assert(bin_deg > 0);
  AngleHistogram h;
  h.bin_deg = bin_deg;
  if (values_deg.empty()) return h;
  const auto [lo, hi] = std::minmax_element(values_deg.begin(), values_deg.end());
  const double first = std::floor(*lo / bin_deg);
  h.origin_deg = static_cast<float>(first * bin_deg);
  const int bins = static_cast<int>(std::floor(*hi / bin_deg) - first) + 1;
  h.counts.assign(bins, 0);
  for (float v : values_deg) {
    const int k = std::clamp(static_cast<int>(std::floor(v / bin_deg) - first), 0, bins - 1);
    ++h.counts[k];
  }
  return h;
}

}  // namespace nerv::snv
