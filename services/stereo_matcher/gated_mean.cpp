#include "gated_mean.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace nerv::stereo {

void gatedMeanRows(const cv::Mat& before, cv::Mat& disparity, const GatedMeanParams& p, int row_begin,
                   int row_end) {
  CV_Assert(before.type() == CV_32FC1 && disparity.type() == CV_32FC1 && before.size() == disparity.size() &&
            before.data != disparity.data);
  const int rows = disparity.rows, cols = disparity.cols, r = p.radius;
  row_begin = std::max(row_begin, 0);
  row_end = std::min(row_end, rows);
  if (r <= 0 || row_begin >= row_end) return;
  std::vector<const float*> window;
  for (int y = row_begin; y < row_end; ++y) {
    const float* c = before.ptr<float>(y);
    float* out = disparity.ptr<float>(y);
    window.clear();
    for (int yy = std::max(0, y - r); yy <= std::min(rows - 1, y + r); ++yy) window.push_back(before.ptr<float>(yy));
    // One pixel; the neighbours are summed in the order (row, column) of the
    // SIMD lanes below, so both give the same floats.
    auto pixel = [&](int x) {
      if (!(c[x] > 0.0f)) return;
      const float gate = std::max(p.range_px, p.range_rel * c[x]);
      float sum = 0.0f, count = 0.0f;
      for (const float* w : window)
        for (int xx = std::max(0, x - r); xx <= std::min(cols - 1, x + r); ++xx)
          if (w[xx] > 0.0f && std::fabs(w[xx] - c[x]) <= gate) {
            sum += w[xx];
            count += 1.0f;
          }
      out[x] = sum / count;  // the pixel itself is always in
    };
    int x = 0;
    for (; x < std::min(r, cols); ++x) pixel(x);
#ifdef __AVX2__
    // Eight pixels at a time where the whole window lies inside the row; the
    // sums stay in registers over the window.
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
    const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    const __m256 range_px = _mm256_set1_ps(p.range_px), range_rel = _mm256_set1_ps(p.range_rel);
    for (; x + 8 <= cols - r; x += 8) {
      const __m256 cv = _mm256_loadu_ps(c + x);
      const __m256 gate = _mm256_max_ps(range_px, _mm256_mul_ps(range_rel, cv));
      __m256 sum = zero, count = zero;
      for (const float* w : window)
        for (int dx = -r; dx <= r; ++dx) {
          const __m256 q = _mm256_loadu_ps(w + x + dx);
          const __m256 in = _mm256_and_ps(_mm256_cmp_ps(q, zero, _CMP_GT_OQ),
                                          _mm256_cmp_ps(_mm256_and_ps(_mm256_sub_ps(q, cv), abs_mask), gate, _CMP_LE_OQ));
          sum = _mm256_add_ps(sum, _mm256_and_ps(in, q));
          count = _mm256_add_ps(count, _mm256_and_ps(in, one));
        }
      const __m256 valid = _mm256_cmp_ps(cv, zero, _CMP_GT_OQ);
      _mm256_storeu_ps(out + x, _mm256_blendv_ps(cv, _mm256_div_ps(sum, count), valid));
    }
#endif
    for (; x < cols; ++x) pixel(x);
  }
}

}  // namespace nerv::stereo
