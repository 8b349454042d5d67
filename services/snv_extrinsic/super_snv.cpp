#include "super_snv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
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

namespace {

// atan(x) for any finite x (Cephes atanf: range reduction to |x| <= tan(pi/8),
// then a degree-9 odd polynomial). Branch-free so the caller's loop vectorises.
inline float atanPoly(float x) {
  const float ax = std::abs(x);
  const bool big = ax > 2.414213562373095f, mid = ax > 0.4142135623730950f;
  const float t = big ? -1.0f / (big ? ax : 1.0f) : (mid ? (ax - 1.0f) / (ax + 1.0f) : ax);
  const float y0 = big ? 1.5707963267948966f : (mid ? 0.7853981633974483f : 0.0f);
  const float z = t * t;
  const float p = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
                   3.33329491539e-1f) * z * t + t;
  const float y = y0 + p;
  return x < 0 ? -y : y;
}

inline uint32_t orderedBits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b ^ ((b >> 31) ? 0xFFFFFFFFu : 0x80000000u);
}

}  // namespace

void normalAnglesDeg(const cv::Vec3f* normals, int count, float* pitch_deg, float* roll_deg) {
  const double to_deg = 180.0 / CV_PI;
  const float* n = normals[0].val;
  for (int i = 0; i < count; ++i) {
    // atan2(y, x) = atan(y / x) for x > 0; the rest is fixed up below.
    const float x = -n[3 * i + 1];
    const float inv = 1.0f / (x > 0 ? x : 1.0f);
    pitch_deg[i] = static_cast<float>(atanPoly(-n[3 * i + 2] * inv) * to_deg);
    roll_deg[i] = static_cast<float>(atanPoly(-n[3 * i] * inv) * to_deg);
  }
  for (int i = 0; i < count; ++i)
    if (!(-n[3 * i + 1] > 0)) {
      pitch_deg[i] = normalPitchDeg(normals[i]);
      roll_deg[i] = normalRollDeg(normals[i]);
    }
}

void sortAngles(std::vector<float>& values) {
  const size_t n = values.size();
  if (n < 2) return;
  std::vector<float> tmp(n);
  float* src = values.data();
  float* dst = tmp.data();
  for (int shift : {0, 11, 22}) {
    uint32_t counts[2048] = {0};
    for (size_t i = 0; i < n; ++i) ++counts[(orderedBits(src[i]) >> shift) & 2047u];
    uint32_t sum = 0;
    for (uint32_t& c : counts) {
      const uint32_t k = c;
      c = sum;
      sum += k;
    }
    for (size_t i = 0; i < n; ++i) dst[counts[(orderedBits(src[i]) >> shift) & 2047u]++] = src[i];
    std::swap(src, dst);
  }
  // Three passes: the sorted data ended in tmp.
  values.swap(tmp);
}

float sortedModeDeg(const std::vector<float>& sorted, float bin_deg) {
  CV_Assert(bin_deg > 0);
  if (sorted.empty()) return std::numeric_limits<float>::quiet_NaN();
  // The same arithmetic as buildAngleHistogram, so the same bin for every value.
  const double first = std::floor(sorted.front() / bin_deg);
  const int bins = static_cast<int>(std::floor(sorted.back() / bin_deg) - first) + 1;
  auto binOf = [&](float v) {
    return std::clamp(static_cast<int>(std::floor(v / bin_deg) - first), 0, bins - 1);
  };
  int best = 0, best_count = 0, bin = binOf(sorted[0]), run = 0;
  for (float v : sorted) {
    const int k = binOf(v);
    if (k != bin) {
      if (run > best_count) best = bin, best_count = run;
      bin = k;
      run = 0;
    }
    ++run;
  }
  if (run > best_count) best = bin;
  const float origin = static_cast<float>(first * bin_deg);
  return origin + (static_cast<float>(best) + 0.5f) * bin_deg;
}

}  // namespace nerv::snv
