#include "super_snv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

void sampleRange(const float* v, size_t n, float& lo, float& hi) {
  if (n == 0) {
    lo = hi = std::numeric_limits<float>::quiet_NaN();
    return;
  }
  // Lane-wise minima and maxima vectorise (a scalar float min/max reduction
  // does not without -ffinite-math-only); the lanes are reduced at the end.
  constexpr size_t kLanes = 16;
  float mn[kLanes], mx[kLanes];
  for (size_t j = 0; j < kLanes; ++j) mn[j] = mx[j] = v[0];
  size_t i = 0;
  for (; i + kLanes <= n; i += kLanes)
    for (size_t j = 0; j < kLanes; ++j) {
      mn[j] = v[i + j] < mn[j] ? v[i + j] : mn[j];
      mx[j] = v[i + j] > mx[j] ? v[i + j] : mx[j];
    }
  for (; i < n; ++i) {
    mn[0] = v[i] < mn[0] ? v[i] : mn[0];
    mx[0] = v[i] > mx[0] ? v[i] : mx[0];
  }
  lo = mn[0];
  hi = mx[0];
  for (size_t j = 1; j < kLanes; ++j) {
    lo = mn[j] < lo ? mn[j] : lo;
    hi = mx[j] > hi ? mx[j] : hi;
  }
}

namespace {

void insertionSort(float* a, size_t n) {
  for (size_t i = 1; i < n; ++i) {
    const float x = a[i];
    size_t j = i;
    for (; j > 0 && a[j - 1] > x; --j) a[j] = a[j - 1];
    a[j] = x;
  }
}

// Bucket ("spread") sort of a[0, n), tmp[0, n) scratch. The bucket of a value
// is floor(F(a)) with F a piecewise-linear approximation of the sample's CDF
// scaled to n (from a 256-bin histogram over [min, max]): F is monotone, so the
// buckets are ordered, and it spreads the values ~1 per bucket even when most
// of them sit in a narrow core (evenly spaced buckets left ~20 per core bucket
// for the insertion sort). One insertion pass over the whole array (inversions
// only inside buckets) finishes it; buckets of more than 32 values are sorted
// first, recursively. (An LSD radix sort over the float bits serialised on the
// few top-digit buckets of such a narrow range.) Positions are float and the
// scratch is kept per thread and depth: 2.2x faster than double positions and
// fresh vectors (60 -> 27 us for 6.5k KITTI-like angles); rounding can only put
// a value in a neighbouring bucket, and the insertion pass sorts any order.
void spreadSort(float* a, size_t n, float* tmp, int depth) {
  if (n <= 32) return insertionSort(a, n);
  float lo, hi;
  sampleRange(a, n, lo, hi);
  if (!(lo < hi)) return;  // all equal
  // (A range beyond 1e30 would overflow the float positions below: std::sort.)
  if (depth > 6 || !std::isfinite(lo) || !std::isfinite(hi) || static_cast<double>(hi) - lo > 1e30)
    return std::sort(a, a + n);
  constexpr uint32_t kCoarse = 256;
  const float scale = static_cast<float>(kCoarse / (static_cast<double>(hi) - lo)), lo_f = lo;
  // Scratch per recursion depth, kept by the thread (no allocation per call).
  thread_local std::vector<float> pos_buf[8];
  thread_local std::vector<uint32_t> key_buf[8], end_buf[8];
  std::vector<float>& pos = pos_buf[depth];
  std::vector<uint32_t>& key = key_buf[depth];
  std::vector<uint32_t>& end = end_buf[depth];
  pos.resize(n);
  key.resize(n);
  end.assign(n, 0);
  uint32_t hist[kCoarse] = {0};
  for (size_t i = 0; i < n; ++i) {
    pos[i] = (a[i] - lo_f) * scale;
    key[i] = std::min(kCoarse - 1, static_cast<uint32_t>(pos[i]));
  }
  for (size_t i = 0; i < n; ++i) ++hist[key[i]];
  float cum[kCoarse], width[kCoarse];
  uint32_t run = 0;
  for (uint32_t b = 0; b < kCoarse; ++b) {
    cum[b] = static_cast<float>(run);
    width[b] = static_cast<float>(hist[b]);
    run += hist[b];
  }
  // Within coarse bin b the position is spread linearly over [cum_b, cum_b + hist_b).
  // Any rounding here only moves a value to a neighbouring bucket: the final
  // insertion pass sorts whatever the buckets leave, so the result is exact.
  const uint32_t last = static_cast<uint32_t>(n - 1);
  constexpr float kBelowOne = 1.0f - 1.0f / (1 << 20);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t b = key[i];
    const float frac = std::clamp(pos[i] - static_cast<float>(b), 0.0f, kBelowOne);
    key[i] = std::min(last, static_cast<uint32_t>(cum[b] + frac * width[b]));
  }
  for (size_t i = 0; i < n; ++i) ++end[key[i]];
  uint32_t sum = 0, largest = 0;
  for (uint32_t& e : end) {  // bucket starts; the scatter below turns them into ends
    const uint32_t c = e;
    e = sum;
    sum += c;
    largest = std::max(largest, c);
  }
  for (size_t i = 0; i < n; ++i) tmp[end[key[i]]++] = a[i];
  std::copy(tmp, tmp + n, a);
  if (largest > 32)
    for (uint32_t b = 0, begin = 0; b < n; begin = end[b++])
      if (end[b] - begin > 32) spreadSort(a + begin, end[b] - begin, tmp, depth + 1);
  insertionSort(a, n);
}

}  // namespace

void sortAngles(std::vector<float>& values) {
  if (values.size() < 2) return;
  thread_local std::vector<float> tmp;  // kept: no allocation per call
  tmp.resize(values.size());
  spreadSort(values.data(), values.size(), tmp.data(), 0);
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
  // Bins of a chunk first (vectorised), then the runs of equal bins.
  constexpr size_t kChunk = 256;
  int bin_of[kChunk];
  int best = 0, best_count = 0, bin = binOf(sorted[0]), run = 0;
  for (size_t c = 0; c < sorted.size(); c += kChunk) {
    const size_t m = std::min(kChunk, sorted.size() - c);
    const float* v = sorted.data() + c;
    for (size_t i = 0; i < m; ++i) bin_of[i] = binOf(v[i]);
    for (size_t i = 0; i < m; ++i) {
      const int k = bin_of[i];
      if (k != bin) {
        if (run > best_count) best = bin, best_count = run;
        bin = k;
        run = 0;
      }
      ++run;
    }
  }
  if (run > best_count) best = bin;
  const float origin = static_cast<float>(first * bin_deg);
  return origin + (static_cast<float>(best) + 0.5f) * bin_deg;
}

}  // namespace nerv::snv
