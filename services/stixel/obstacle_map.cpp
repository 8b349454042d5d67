#include "obstacle_map.hpp"

#include <algorithm>
#include <limits>

#ifdef __AVX2__
#include <immintrin.h>
#endif

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
  float* out = nullptr;
  size_t n = 0;
#ifdef __AVX2__
  // Eight columns per step, the strip's last lanes masked; the samples are
  // taken in the scalar loop's order (rows, then columns), so nth_element
  // sees the same sequence. Without a branch per pixel: each lane's value is
  // written to the next free slot and the slot advances by its test (the
  // scalar loop's pixel tests mispredict often on a ragged disparity).
  const __m256 v_lo = _mm256_set1_ps(lo), v_hi = _mm256_set1_ps(hi);
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const size_t most = static_cast<size_t>(std::max(0, v1 - v0 + 1)) * std::max(0, u1 - u0) + 8;
  if (samples.size() < most) samples.resize(most);  // grows only: no clearing per call
  out = samples.data();
  for (int v = v0; v <= v1; ++v) {
    const float* row = obstacle_map.ptr<float>(v);
    for (int u = u0; u < u1; u += 8) {
      const __m256i in_strip = _mm256_cmpgt_epi32(_mm256_set1_epi32(u1 - u), lanes);
      const __m256 x = _mm256_maskload_ps(row + u, in_strip);  // masked lanes: 0, dropped below
      const __m256 in = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(x, v_lo, _CMP_GE_OQ), _mm256_cmp_ps(x, v_hi, _CMP_LT_OQ)),
                                      _mm256_castsi256_ps(in_strip));
      const unsigned m = static_cast<unsigned>(_mm256_movemask_ps(in));
      if (m == 0) continue;
      alignas(32) float vals[8];
      _mm256_store_ps(vals, x);
      for (int j = 0; j < 8; ++j) {
        out[n] = vals[j];
        n += (m >> j) & 1u;
      }
    }
  }
#else
  // The same order, without a branch per pixel: every value is written to the next
  // free slot, which advances by its test (NaN fails it).
  const size_t most = static_cast<size_t>(std::max(0, v1 - v0 + 1)) * std::max(0, u1 - u0);
  if (samples.size() < most) samples.resize(most);
  out = samples.data();
  for (int v = v0; v <= v1; ++v) {
    const float* row = obstacle_map.ptr<float>(v);
    for (int u = u0; u < u1; ++u) {
      const float x = row[u];
      out[n] = x;
      n += static_cast<size_t>((x >= lo) & (x < hi));
    }
  }
#endif
  if (n == 0) return 0.0f;
  std::nth_element(out, out + n / 2, out + n);
  return out[n / 2];
}

}  // namespace nerv::stixel
